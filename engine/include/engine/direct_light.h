// Direct lighting of a G-buffer by the scene's punctual lights, with shadow maps that the
// compute rasterizer renders each frame (spot: one perspective view, or a cube when the cone
// is too wide for one; point: a cube of 6 views; directional: an orthographic view that
// covers the scene bounds).
#pragma once

#include <vector>

#include "engine/gbuffer.h"
#include "engine/rasterizer.h"
#include "shared/direct_light.h"

namespace engine {

struct DirectLightSettings {
  uint32_t shadowResolution = 1024;  // [16, 4096] texels per side; cost ~ resolution^2 per view
  bool shadows = true;               // off: every light is unoccluded
};

// GPU light records and shadow views for a scene (CPU only, testable without a device).
struct LightSetup {
  std::vector<gpu::GpuLight> lights;
  std::vector<gpu::ShadowView> views;
};
LightSetup buildLightSetup(const Scene& scene, const DirectLightSettings& settings);

class DirectLighting {
 public:
  DirectLighting(Context& ctx, const Scene& scene, const DirectLightSettings& settings);

  // Shadow maps, then radiance = sum over lights of BRDF * cos * irradiance * visibility into
  // `radiance` (R32G32B32A32_SFLOAT storage image in GENERAL layout).
  void record(VkCommandBuffer cmd, const SceneGpu& scene, Rasterizer& rasterizer,
              const GBuffer& gbuffer, const View& view, Image& radiance,
              GpuProfiler* profiler = nullptr);

  // The scene's lights changed (moved, turned, added): new light records and shadow views, the
  // shadow-map memory grown when there are more views. Blocking uploads, between frames; the
  // program is kept, so a host that moves a light each frame does not rebuild its pipeline.
  void setLights(Context& ctx, const Scene& scene);
  const LightSetup& setup() const { return setup_; }

 private:
  void upload(Context& ctx, const Scene& scene);

  DirectLightSettings settings_;
  LightSetup setup_;
  ComputeProgram program_;
  Buffer lights_;
  Buffer views_;
  Buffer shadowMaps_;  // one visibility buffer per view, back to back
};

}  // namespace engine
