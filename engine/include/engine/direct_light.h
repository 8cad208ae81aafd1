// Direct lighting of a G-buffer by the scene's punctual lights, with shadow maps that the
// compute rasterizer renders each frame (spot: one perspective view, or a cube when the cone
// is too wide for one; point: a cube of 6 views; directional: an orthographic view that
// covers the scene bounds).
#pragma once

#include <span>
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

// A shadow map rendered elsewhere for one of the setup's views (the indirect-light module's
// light view, gi::LightViewOutput): shadowResolution^2 visibility texels in the rasterizer's
// format and the view they were rendered with.
struct GivenShadowMap {
  uint32_t view = 0;  // index into LightSetup::views
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  glm::mat4 viewProj{1.0f};
};

// The ShadowView of a given map: its matrix, and the world size of one of its `resolution`
// texels, 2 / (|row 0 of viewProj| x resolution) per metre of distance (perspective) or in
// metres (orthographic).
gpu::ShadowView givenShadowView(const glm::mat4& viewProj, uint32_t resolution);

class DirectLighting {
 public:
  DirectLighting(Context& ctx, const Scene& scene, const DirectLightSettings& settings);

  // Shadow maps, then radiance = sum over lights of BRDF * cos * irradiance * visibility into
  // `radiance` (R32G32B32A32_SFLOAT storage image in GENERAL layout).
  // A view with a `given` map copies it instead of rasterizing its own (one triangle setup per
  // light and frame when the module's light views serve as shadow maps).
  void record(VkCommandBuffer cmd, const SceneGpu& scene, Rasterizer& rasterizer,
              const GBuffer& gbuffer, const View& view, Image& radiance,
              GpuProfiler* profiler = nullptr, std::span<const GivenShadowMap> given = {});

  // The scene's lights changed (moved, turned, added): new light records and shadow views, the
  // shadow-map memory grown when there are more views. Blocking uploads, between frames; the
  // program is kept, so a host that moves a light each frame does not rebuild its pipeline.
  void setLights(Context& ctx, const Scene& scene);
  const LightSetup& setup() const { return setup_; }
  uint32_t shadowResolution() const { return settings_.shadowResolution; }

 private:
  void upload(Context& ctx, const Scene& scene);

  DirectLightSettings settings_;
  LightSetup setup_;
  ComputeProgram program_;
  Buffer lights_;
  Buffer views_;
  Buffer shadowMaps_;        // one visibility buffer per view, back to back
  bool viewsGiven_ = false;  // views_ holds given maps' views (the next frame restores its own)
};

}  // namespace engine
