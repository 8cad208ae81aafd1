// The six VSGL attribute pyramids of an RSM (shaders/shared/vsgl_attributes.h): level 0 written
// by vsgl_attributes.comp, the other levels by exact-mean reductions.
#pragma once

#include <array>

#include "passes/mip_pyramid.h"
#include "passes/rsm.h"
#include "shared/vsgl_attributes.h"

namespace gi {

class VsglAttributes {
 public:
  VsglAttributes(engine::Context& ctx, uint32_t size);  // size: the RSM's, a power of two

  void record(VkCommandBuffer cmd, ReflectiveShadowMap& rsm, const RsmView& view,
              const MipPyramid& mips, engine::GpuProfiler* profiler = nullptr);

  engine::Image& pyramid(int attribute) { return pyramids_.at(attribute); }

 private:
  uint32_t size_;
  engine::ComputeProgram program_;
  std::array<engine::Image, VSGL_ATTR_COUNT> pyramids_;
};

}  // namespace gi
