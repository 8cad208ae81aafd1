// The six VSGL attribute pyramids of an RSM (shaders/shared/vsgl_attributes.h): level 0 written
// by vsgl_attributes.comp, the other levels by exact-mean reductions.
#pragma once

#include <array>
#include <string>

#include "passes/mip_pyramid.h"
#include "passes/rsm.h"
#include "shared/vsgl_attributes.h"

namespace gi {

class VsglAttributes {
 public:
  // `size`: the pyramids' base, a power of two at least as large as every source it will read.
  // `passPrefix` is put before the profiler's pass names ("vsgl attributes", "attribute
  // mipmapping"), so that the camera's importance pyramids are timed apart from the light's.
  VsglAttributes(engine::Context& ctx, uint32_t size, std::string passPrefix = {});

  // Level 0 from `vpls` (any extent up to size x size; the rest of level 0 is zero, so padding
  // carries no power and no PDF, vsgl-math.md 5.3) and the normals of `surface`, then the mips.
  // The padding is cleared when the source extent changes, so every recorded command buffer
  // must be submitted.
  // specular = false (the effect planner: no surface has a specular lobe, so the specular
  // pyramids' level 0 would be zero) leaves the specular pyramids zero at every level, cleared
  // once while the setting stays off, and skips their lobes and mip passes: the same zeros.
  // broadReflections: a texel's broad reflection joins its diffuse lobe (Settings::
  // broadReflections); false keeps every reflection in the glossy lobe.
  void record(VkCommandBuffer cmd, VplImages& vpls, engine::GBuffer& surface, const RsmView& view,
              const MipPyramid& mips, engine::GpuProfiler* profiler = nullptr, bool specular = true,
              bool broadReflections = false);

  engine::Image& pyramid(int attribute) { return pyramids_.at(attribute); }

 private:
  // Zeroes every level of pyramids [first, end), between compute passes.
  void clearLevels(VkCommandBuffer cmd, int first, int end);

  uint32_t size_;
  std::string passPrefix_;
  glm::uvec2 lastExtent_{0u};           // source extent of the last record: the padding is zero
  bool specularZero_ = false;           // the specular pyramids are zero at every level
  engine::ComputeProgram programs_[2];  // vsgl_attributes.comp without, with specular lobes
  std::array<engine::Image, VSGL_ATTR_COUNT> pyramids_;
};

}  // namespace gi
