// Imperfect shadow maps for VSGLs (Ritschel et al. 2008; vsgl-math.md section 8; formats and
// passes in shaders/shared/ism.h, design and measurements in docs/techniques/ism.md).
//   recordPoints (scene change): an area-proportional pool of surface points as (triangle,
//     barycentrics), generated on the GPU from the scene buffers: "ism points".
//   recordPositions (geometry or VSGL count change): the pool points' positions from the
//     current vertex buffer: "ism positions".
//   recordSplat, recordPullPush (new VSGLs): one paraboloid depth map per VSGL splatted into one
//     atlas, pull-push hole filling: "ism splat", "ism pull-push". recordBuild runs all three.
//   Shading passes include shaders/common/ism_lookup.glsl, bind atlas() and pass params().
// Everything is recorded into the caller's command buffer; nothing here submits or waits.
#pragma once

#include "engine/gbuffer.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/scene_gpu.h"
#include "engine/view.h"
#include "gi/settings.h"
#include "shared/ism.h"

namespace gi {

// IsmSettings (fields, defaults, ranges, costs) is public: gi/include/gi/settings.h.

// Throws engine::Error naming the field when a setting is outside its range.
void validateIsmSettings(const IsmSettings& settings);

class Ism {
 public:
  // Allocates the atlas for up to `maxVsgls` VSGLs, [1, 65535] (its side must fit the device's
  // image limit: 16384 texels allow 4096 VSGLs at 256^2) and the point pool; the settings are fixed
  // for the object's lifetime (recreate to change them). Submits nothing on a host's device: the
  // images get their GENERAL layout through engine::initialLayout.
  Ism(engine::Context& ctx, const IsmSettings& settings, uint32_t maxVsgls);

  // Regenerates the point pool from `scene` (call after a scene change, not per frame); grows
  // the scratch buffer when the scene has more triangles than before (the previous one must
  // then no longer be in flight).
  void recordPoints(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                    engine::GpuProfiler* profiler = nullptr);

  // Builds the maps of the first `vsglCount` records of `vsgls` (gpu::Vsgl) with the current
  // vertex positions of `scene` (same topology as at recordPoints): recordPositions,
  // recordSplat, then recordPullPush.
  void recordBuild(VkCommandBuffer cmd, const engine::SceneGpu& scene, const engine::Buffer& vsgls,
                   uint32_t vsglCount, engine::GpuProfiler* profiler = nullptr);
  // The parts of recordBuild. recordPositions writes positions() for `vsglCount` VSGLs' point
  // subsets from the current vertex buffer; recordSplat reads them, so it needs a
  // recordPositions for the same geometry and count before it (in this frame or an earlier
  // one). After recordSplat level 0 of the atlas holds the raw splats (ISM_EMPTY where no
  // point landed).
  void recordPositions(VkCommandBuffer cmd, const engine::SceneGpu& scene, uint32_t vsglCount,
                       engine::GpuProfiler* profiler = nullptr);
  void recordSplat(VkCommandBuffer cmd, const engine::Buffer& vsgls, uint32_t vsglCount,
                   engine::GpuProfiler* profiler = nullptr);
  void recordPullPush(VkCommandBuffer cmd, uint32_t vsglCount,
                      engine::GpuProfiler* profiler = nullptr);

  // The debug view: ismVisibility of VSGL `vsglIndex` at every pixel of `gbuffer` (seen through
  // `view`) into `out` (R32_SFLOAT storage image of the G-buffer's size; moved to GENERAL).
  // Background pixels get 1. Pass name "ism visibility".
  void recordVisibility(VkCommandBuffer cmd, const engine::GBuffer& gbuffer,
                        const engine::View& view, const engine::Buffer& vsgls, uint32_t vsglIndex,
                        engine::Image& out, engine::GpuProfiler* profiler = nullptr);

  // R32_UINT image in GENERAL layout, tiles as in shaders/shared/ism.h, mip levels = the
  // pull-push pyramid. Bind level 0 as the includer's `ismAtlas`
  // (engine::Binding::storageImage(atlas(), 0)) after recordBuild; recordBuild ends with a
  // compute barrier, so a compute pass recorded after it may read it.
  const engine::Image& atlas() const { return atlas_; }
  engine::Image& atlas() { return atlas_; }  // for readback (tests, tools)
  // Tile k's first texel in the atlas.
  glm::uvec2 tileOrigin(uint32_t k) const;
  const engine::Buffer& points() const { return points_; }  // gpu::IsmPoint[pointCount]
  // RGBA32F, ISM_POSITIONS_WIDTH x pointCount / ISM_POSITIONS_WIDTH (only the points of the
  // subsets in use are written).
  const engine::Image& positions() const { return positions_; }
  // The lookup parameters for ismVisibility (IsmParams in the shading pass's push constants).
  gpu::IsmParams params() const;
  const IsmSettings& settings() const { return settings_; }
  uint32_t maxVsgls() const { return maxVsgls_; }

 private:
  void checkCount(uint32_t vsglCount) const;  // throws unless vsglCount <= maxVsgls()

  engine::Context& ctx_;
  IsmSettings settings_;
  uint32_t maxVsgls_;
  uint32_t pointsTriangleCount_ = 0;  // triangles of the scene the pool was made for
  bool pointsRecorded_ = false;
  engine::ComputeProgram area_;
  engine::ComputeProgram scan_;
  engine::ComputeProgram pointsPrograms_[2];  // without and with the alpha test
  engine::ComputeProgram positionsProgram_;
  engine::ComputeProgram splat_;
  engine::ComputeProgram pull_;
  engine::ComputeProgram push_;
  engine::ComputeProgram visibility_;
  uint32_t tilesPerRowLog2_ = 0;
  engine::Buffer cdf_;  // float per triangle: areas, then their inclusive prefix sums
  engine::Buffer points_;
  engine::Image positions_;
  engine::Image atlas_;
};

}  // namespace gi
