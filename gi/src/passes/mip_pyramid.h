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

 private:
  engine::ComputeProgram program_;
};

}  // namespace gi
