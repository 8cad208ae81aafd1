// VSGL shading: indirect diffuse and glossy radiance of every G-buffer pixel from the frame's
// VSGLs (shaders/gi/vsgl_shade.comp, layout in shaders/shared/vsgl_shade.h), or from the VPL
// baseline's point lights (shaders/gi/vpl_shade.comp, the same bindings).
#pragma once

#include <array>
#include <optional>

#include "engine/gbuffer.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/view.h"
#include "shared/ism.h"
#include "shared/vsgl_shade.h"

namespace gi {

// The two RGBA32F outputs, created in GENERAL layout.
struct IndirectImages {
  engine::Image diffuse;
  engine::Image glossy;
};
IndirectImages createIndirectImages(engine::Context& ctx, uint32_t width, uint32_t height);

class VsglShade {
 public:
  explicit VsglShade(engine::Context& ctx);

  // The VSGL shading pass's inputs besides the G-buffer.
  struct Inputs {
    const engine::Buffer* vsgls = nullptr;  // gpu::Vsgl[vsglCount]
    uint32_t vsglCount = 0;
    uint32_t flags = 0;                       // VSGL_SHADE_*: the variant
    const engine::Image* ismAtlas = nullptr;  // Ism::atlas(), bound even when not read
    gpu::IsmParams ism{};                     // Ism::params()
    // VSGL_SHADE_QUEUE: the level's queue (shared/adaptive_shading.h, its head holds the
    // indirect dispatch) and the level; `out` is then that level's images.
    const engine::Buffer* queue = nullptr;
    uint32_t level = 0;
    float cullBudget = 0.0f;  // VSGL_SHADE_CULL: tau (CullingSettings::budget)
    // The records are the VPL baseline's point lights (VSGL_RULE_POINT), shaded by
    // vpl_shade.comp, which reads VSGL_SHADE_GLOSSY, _VISIBILITY, _SKIP_SKY and _DIFFUSE_LOBES
    // (no queue, no culling; its emitters are always planar).
    bool points = false;
  };

  // `camera`: the G-buffer camera's view (positions are rebuilt relative to its eye,
  // engine::relativeUnprojection). The first record with a given `in.flags` and ISM filter
  // (`in.ism.pcf`) compiles that variant of the pass (see VSGL_SHADE_VARIANTS).
  void record(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
              const Inputs& in, IndirectImages& out, engine::GpuProfiler* profiler = nullptr);

  // VSGL culling's counts: zeroed before a frame's first record(), copied for the host after
  // its last; lastStats() is valid once that frame has completed (it never waits).
  void recordStatsReset(VkCommandBuffer cmd);
  void recordStatsReadback(VkCommandBuffer cmd);
  gpu::VsglShadeStats lastStats() const;

 private:
  engine::Context* ctx_;
  // [points][ISM filter][flags], each compiled at its first record.
  using Variants = std::array<std::optional<engine::ComputeProgram>, VSGL_SHADE_VARIANTS>;
  std::array<std::array<Variants, ISM_MAX_PCF + 1>, 2> programs_;
  engine::Buffer albedoTable_;  // vec2[17 x 17], gi::ggxSpecularAlbedoNode (sg_lighting.glsl)
  engine::Buffer noQueue_;      // bound as the queue by the variants that do not read one
  engine::Buffer stats_;        // gpu::VsglShadeStats, written by VSGL_SHADE_CULL
  engine::Buffer statsReadback_;
};

}  // namespace gi
