// SG lights from the environment (docs/techniques/environment.md, pass 4): N distant SG lights
// sampled from the converted environment's luminance x solid-angle PDF with the Fibonacci
// lattice, hierarchical warping and the modified-FIS kernel of the VSGL path, then the G-buffer
// shaded with them. Shaders: gi/env_sg_pyramid.comp (+ gi/env_mip_reduce.comp for the mips),
// gi/env_sg_generate.comp, gi/env_sg_shade.comp (layouts in shaders/shared/env_sg.h); CPU twin
// gi/src/reference/env_sg_reference.h, where the estimator and the fit are derived.
//
// Resources (all owned):
//   pyramids  2 x RGBA32F S x S x 2 layers, log2 S + 1 levels, STORAGE | SAMPLED; GENERAL
//             (ENV_SG_RADIANCE: rgb f L, a w lum; ENV_SG_DIRECTION: xyz lum * direction
//             integral, w f lum; w own-hemisphere, f whole-texel solid angle; S = the map's size)
//   lights    storage buffer of maxCount gpu::EnvSgLight (48 bytes each)
//   albedo    the 17 x 17 GGX albedo table of common/sg_lighting.glsl
// Dispatches: record(): (S/8)^2 x 2 groups, one env_mip_reduce dispatch per level and pyramid,
// ceil(N / 64) generation groups; shade(): (W/8) x (H/8) groups, N lights per pixel.
#pragma once

#include "engine/gbuffer.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/view.h"
#include "passes/env_map.h"
#include "passes/vsgl_shade.h"
#include "shared/env_sg.h"

namespace gi {

class EnvSgLights {
 public:
  // `mapSize`: S of the EnvironmentMap this will read (a power of two in [1, 4096]);
  // `maxCount`: the most lights one record() may generate, >= 1. Throws engine::Error otherwise.
  EnvSgLights(engine::Context& ctx, uint32_t mapSize, uint32_t maxCount = ENV_SG_DEFAULT_MAX_COUNT);

  // Builds the attribute pyramids from `environment`'s level 0 (recorded after its record())
  // and generates `count` lights, [1, maxCount], with kernels of PDF mass kernelScale / count,
  // kernelScale in [1, count] ([S3]'s K; 1 = the paper's; larger = blurrier lights). Throws
  // engine::Error for a map of another size or a setting out of range. Afterwards lights()
  // holds the lights, visible to compute shaders recorded later.
  void record(VkCommandBuffer cmd, const EnvironmentMap& environment, uint32_t count,
              float kernelScale = 1.0f, engine::GpuProfiler* profiler = nullptr);

  // The environment's diffuse (albedo applied) and glossy radiance toward the camera at every
  // G-buffer pixel from the last record()'s lights; sky pixels (depth 1) get 0. `camera`: the
  // G-buffer camera's view. Throws engine::Error before any record().
  void shade(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
             IndirectImages& out, engine::GpuProfiler* profiler = nullptr);

  // gpu::EnvSgLight[maxCount], the first count() written (readback for tests and tools).
  const engine::Buffer& lights() const { return lights_; }
  uint32_t count() const { return count_; }
  uint32_t maxCount() const { return maxCount_; }
  // ENV_SG_RADIANCE or ENV_SG_DIRECTION (readback for tests).
  engine::Image& pyramid(uint32_t which) { return pyramids_[which]; }

 private:
  uint32_t size_ = 0;
  uint32_t maxCount_ = 0;
  uint32_t count_ = 0;
  float solidAngleScale_ = 1.0f;  // 4 pi / envSgOwnSolidAngle(S)
  engine::Image pyramids_[ENV_SG_PYRAMIDS];
  engine::Sampler sampler_;  // unused by texelFetch, but a combined image sampler needs one
  engine::Buffer lights_;
  engine::Buffer albedoTable_;
  engine::ComputeProgram build_;
  engine::ComputeProgram mips_;
  engine::ComputeProgram generate_;
  engine::ComputeProgram shade_;
};

}  // namespace gi
