// Adaptive shading (shaders/shared/adaptive_shading.h, docs/techniques/adaptive-shading.md): the
// VSGL sum shaded level by level, coarse to fine, each level deciding per texel whether to
// interpolate its parents or queue it for shading (shaders/gi/adaptive_decide.comp) and then
// shading its queue (vsgl_shade.comp, VSGL_SHADE_QUEUE).
#pragma once

#include <array>
#include <vector>

#include "engine/buffer.h"
#include "engine/gbuffer.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/view.h"
#include "gi/indirect_lighting.h"
#include "passes/vsgl_shade.h"
#include "shared/adaptive_shading.h"

namespace gi {

class AdaptiveShading {
 public:
  // Level images 1..3 and queues 0..3 for a width x height G-buffer.
  AdaptiveShading(engine::Context& ctx, uint32_t width, uint32_t height);

  // Shades `in` (a VsglShade input without VSGL_SHADE_QUEUE) into `out` from `coarsest` down.
  // With `splitGlossy`, texels whose F0 and F90 are 0 are shaded by the variant without the
  // glossy term (PlannerSettings::skipGlossyWithoutSpecular).
  void record(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
              const VsglShade::Inputs& in, const AdaptiveSettings& settings, bool splitGlossy,
              VsglShade& shade, IndirectImages& out, engine::GpuProfiler* profiler = nullptr);

  // The counts of the last recorded frame, valid once its submission has completed.
  ShadingCounts lastCounts() const;

  // For tests: the level images (level 1..3; diffuse without the albedo, alpha = the level the
  // light was shaded at) and the queues (head and texel entries) of the last frame.
  IndirectImages& levelImages(uint32_t level) { return levels_[level - 1]; }
  // `plain`: the queue of texels shaded without the glossy term.
  const engine::Buffer& queue(uint32_t level, bool plain = false) const {
    return plain ? queues_[level].plain : queues_[level].glossy;
  }
  // R32_SFLOAT, the G-buffer's size: the level each pixel's light was shaded at, -1 for the sky
  // (FrameOutput::shadingLevels).
  engine::Image& levelMap() { return levelMap_; }

 private:
  engine::Context* ctx_;
  uint32_t subgroupAlign_;  // AdaptiveDecidePush::orderedAlign when VSGL culling is on
  uint32_t width_, height_;
  engine::ComputeProgram decide_;
  std::vector<IndirectImages> levels_;  // levels 1..ADAPTIVE_MAX_LEVEL
  struct Queues {
    engine::Buffer glossy, plain;
  };
  std::vector<Queues> queues_;  // levels 0..ADAPTIVE_MAX_LEVEL
  engine::Buffer counts_;       // the queues' heads, copied for the host
  engine::Image levelMap_;
};

// The push constants of one level's decision pass from the settings (shared with the CPU twin).
gpu::AdaptiveDecidePush adaptiveDecidePush(const AdaptiveSettings& settings,
                                           const engine::View& camera, uint32_t width,
                                           uint32_t height, uint32_t level, bool splitGlossy);

}  // namespace gi
