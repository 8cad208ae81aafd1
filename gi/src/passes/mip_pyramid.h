// Exact-mean mip pyramids of RGBA32F power-of-two square images (shaders/shared/mip_reduce.h),
// one dispatch per level.
#pragma once

#include "engine/profiler.h"
#include "engine/program.h"

namespace gi {

// An RGBA32F storage image of size x size with the full mip chain, in GENERAL layout, ready to
// be filled at level 0 and reduced. `size` must be a power of two.
engine::Image createPyramid(engine::Context& ctx, uint32_t size);

class MipPyramid {
 public:
  explicit MipPyramid(engine::Context& ctx);

  // Rebuilds levels 1..n-1 of `image` from level 0.
  void record(VkCommandBuffer cmd, engine::Image& image, engine::GpuProfiler* profiler = nullptr,
              const char* passName = "mipmapping") const;
  // The same where only level 0's `extent` (from texel 0, 0) can be non-zero and every texel of
  // every level outside the region it reduces to is already zero: each level is reduced over
  // ceil(extent / 2^level) texels, what the full reduction computes there, and the zeros it would
  // write elsewhere stay (a 320x180 image in a 512^2 pyramid reduces 22 % of level 1).
  void record(VkCommandBuffer cmd, engine::Image& image, glm::uvec2 extent,
              engine::GpuProfiler* profiler = nullptr, const char* passName = "mipmapping") const;

 private:
  engine::ComputeProgram program_;
};

}  // namespace gi
