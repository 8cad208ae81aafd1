// The environment conversion (docs/techniques/environment.md, passes 1 and 2): an
// equirectangular RGBA32F image -> the scaled dual-paraboloid map of shaders/shared/environment.h
// (one RGBA32F 2-layer array image, S x S per layer, full box-filtered mip chain) and its 9 SH
// radiance coefficients (gpu::EnvSh). Shaders: gi/env_paraboloid.comp, gi/env_mip_reduce.comp,
// gi/env_sh.comp (push constants in shared/env_map.h); CPU twin:
// gi/src/reference/env_map_reference.h.
//
// Resources (all owned):
//   staging   host-visible buffer of the last upload's W x H RGBA32F texels
//   equirect  RGBA32F W x H, 1 level, SAMPLED; SHADER_READ_ONLY_OPTIMAL; read with texelFetch
//   map       RGBA32F S x S x 2 layers, log2 S + 1 levels, STORAGE | SAMPLED; always GENERAL
//   sh        storage buffer of one gpu::EnvSh (144 bytes)
// Dispatches of record(): conversion (S/8)^2 x 2 groups; one mip dispatch per level
// ((n/8)^2 x 2 groups); SH projection 1 group of 128 threads over the level of size
// min(S, ENV_SH_LEVEL_SIZE = 64).
#pragma once

#include "engine/image_io.h"
#include "engine/profiler.h"
#include "engine/program.h"

namespace gi {

class EnvironmentMap {
 public:
  // `size`: S, texels per side of level 0 of each layer, a power of two in [1, 4096]. Throws
  // engine::Error for another size or when the device cannot sample R32G32B32A32_SFLOAT with
  // linear filtering or store to it.
  explicit EnvironmentMap(engine::Context& ctx, uint32_t size = 256);

  // Stages `equirect` (linear RGB, y up, row 0 at the top; the conventions of
  // reference/env_paraboloid.h; alpha ignored) in host-visible memory for the next record(),
  // which copies and converts it: nothing is submitted here, so a host's device works too.
  // Throws engine::Error naming the problem for an empty image, a pixel count that does not
  // match width x height, a size beyond the device's image limit, or a non-finite or negative
  // rgb value (with its pixel). The staging memory lives until the next upload.
  void upload(engine::Context& ctx, const engine::ImageRgba32f& equirect);

  // Whether an upload waits for record().
  bool pending() const { return pending_; }
  // Copy (once per upload), conversion, mips and SH of the last uploaded image. Afterwards
  // map() holds the converted environment and sh() its coefficients, visible to compute
  // shaders recorded later (the map through a combined image sampler with sampler(), or
  // storage image views, in GENERAL layout). Throws engine::Error before any upload.
  void record(VkCommandBuffer cmd, engine::GpuProfiler* profiler = nullptr);

  const engine::Image& map() const { return map_; }
  engine::Image& map() { return map_; }  // readback (tests and tools) needs a mutable Image
  // Trilinear, clamp to edge: the FIS lookups' sampler for map().
  const engine::Sampler& sampler() const { return sampler_; }
  engine::Binding mapBinding() const { return engine::Binding::sampled(map_, sampler_.handle()); }
  const engine::Buffer& sh() const { return sh_; }
  uint32_t size() const { return size_; }
  uint32_t levels() const { return map_.desc().mips; }
  // The level that the SH pass projects: the one of size min(S, 64).
  uint32_t shLevel() const { return shLevel_; }
  bool hasEnvironment() const { return equirect_.handle() != VK_NULL_HANDLE; }

 private:
  uint32_t size_ = 0;
  uint32_t shLevel_ = 0;
  uint32_t maxImageDimension_ = 0;
  engine::Image equirect_;
  engine::Buffer staging_;  // the last upload's texels, copied by the next record()
  bool pending_ = false;
  engine::Image map_;
  engine::Sampler sampler_;
  engine::Buffer sh_;
  engine::ComputeProgram convert_;
  engine::ComputeProgram mips_;
  engine::ComputeProgram project_;
};

}  // namespace gi
