// The host's G-buffer depth and normal, in the encodings it renders (gi::DepthEncoding,
// gi::NormalEncoding), converted into the module's own by gbuffer_convert.comp (formats:
// shaders/shared/gbuffer_convert.h). Runs only when an encoding differs from the module's.
#pragma once

#include "engine/image.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "shared/gbuffer_convert.h"

namespace gi {

class GBufferConvert {
 public:
  GBufferConvert(engine::Context& ctx, uint32_t width, uint32_t height);

  // Reads `hostDepth` and `hostNormal` (sampled views, in GENERAL layout) into depth() and
  // normal(), and makes them visible to the later compute passes.
  void record(VkCommandBuffer cmd, const engine::Image& hostDepth, const engine::Image& hostNormal,
              const gpu::GBufferConvertPush& push, engine::GpuProfiler* profiler);

  engine::Image& depth() { return depth_; }    // R32_SFLOAT, forward NDC, 1 = sky
  engine::Image& normal() { return normal_; }  // R16G16_SNORM, octahedral

 private:
  engine::ComputeProgram program_;
  engine::Sampler sampler_;  // nearest: texelFetch only
  engine::Image depth_;
  engine::Image normal_;
};

}  // namespace gi
