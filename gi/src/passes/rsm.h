// The reflective shadow map of one light: the G-buffer resolve rendered from the light (same
// rasterizer, same surface code as the camera) followed by rsm_flux.comp, which turns every
// texel into a virtual point light with a position relative to the light and its flux
// (formats: shaders/shared/rsm_flux.h).
#pragma once

#include <string>
#include <vector>

#include "engine/gbuffer.h"
#include "engine/rasterizer.h"
#include "engine/scene.h"

namespace gi {

// How the RSM sees its light. Spot lights: a square perspective frustum whose half angle is the
// outer cone (corner texels outside the cone get zero power); directional lights: an
// orthographic view enclosing the scene; point lights: six, the faces of a cube around the light
// (makeRsmViews, docs/techniques/point-lights.md).
struct RsmView {
  engine::View view;  // world -> clip; width = height = size
  // The rasterizer's transform: (world - origin) -> clip, from the projection and the light's
  // rotation directly, so that depths do not carry the rounding of a world-space translation.
  engine::RasterTransform raster;
  glm::mat4 invViewProjRelative{1.0f};  // NDC -> offset from `origin` (no translation inside)
  glm::vec3 origin{0.0f};               // light position (spot) or orthographic eye (directional)
  glm::vec3 axis{0.0f, 0.0f, -1.0f};    // unit direction the light travels
  bool perspective = true;
  float tanHalfAngle = 0.0f;  // spot: tan of the frustum's half angle
  float texelArea = 0.0f;     // spot: on the unit-distance plane; directional: m^2
};

// Throws engine::Error for point lights (makeRsmViews) and for spots wider than
// kMaxRsmHalfAngle.
RsmView makeRsmView(const engine::Scene& scene, const engine::Light& light, uint32_t size);
// The same from the scene's bounds (all the scene the view needs: its depth range and, for a
// directional light, the orthographic box).
RsmView makeRsmView(const engine::Bounds& bounds, const engine::Light& light, uint32_t size);

// Every view of `light`: one for a spot or directional light; for a point light the six 90 degree
// faces of a cube centred on it, looking along +x, -x, +y, -y, +z, -z (kCubeFaceAxes), which
// tile the sphere of directions with no texel centre on two faces.
std::vector<RsmView> makeRsmViews(const engine::Bounds& bounds, const engine::Light& light,
                                  uint32_t size);
constexpr uint32_t kCubeFaces = 6;

// A single perspective view cannot hold a cone much wider than this (texel density at its rim
// falls as cos^3); wider spot lights are refused rather than sampled badly.
constexpr float kMaxRsmHalfAngle = 1.3f;

// Exact solid angle of the square frustum with half angle `halfAngle` on both axes:
// 4 asin(sin^2 halfAngle) (vsgl-math.md section 2).
double frustumSolidAngle(double halfAngle);

// What the flux pass emits from: a light (colour * intensity, KHR spot falloff) or the camera's
// importance for the view-dependent PDF (unit emission, no falloff: vsgl-math.md section 7).
struct FluxSource {
  glm::vec3 radiance{1.0f};       // W/sr (spot), W/m^2 (directional), 1 (importance)
  glm::vec2 falloff{0.0f, 1.0f};  // saturate(cos * x + y)^2; (0, 1) = no falloff
  // A spot's range in metres, 0 = none: the flux carries KHR_lights_punctual's window
  // clamp(1 - (d / range)^4, 0, 1) at the texel's distance d, as the light's direct light does.
  float range = 0.0f;
};
FluxSource lightFluxSource(const engine::Light& light);

// The importance "RSM" of a camera: its own G-buffer seen as texels of a unit-intensity spot
// without falloff at the eye, so the same flux / attribute / generation passes turn camera pixels
// into importance VSGLs (Tokuyoshi's BRSM stage A). Works for non-square images; texelArea is
// the pixel's area on the plane at unit distance (perspective) or in m^2 (orthographic).
RsmView cameraImportanceView(const engine::View& view);

// The flux pass's outputs (formats: shaders/shared/rsm_flux.h), width x height RGBA32F.
struct VplImages {
  engine::Image position;
  engine::Image diffuse;
  engine::Image specular;
  uint32_t width = 0;
  uint32_t height = 0;
};
VplImages createVplImages(engine::Context& ctx, uint32_t width, uint32_t height);

// rsm_flux.comp over any G-buffer (a light's or the camera's).
class FluxPass {
 public:
  // `passName`: the profiler's name for it (the camera's importance flux is timed apart).
  explicit FluxPass(engine::Context& ctx, std::string passName = "rsm flux");
  void record(VkCommandBuffer cmd, engine::GBuffer& surface, const RsmView& view,
              const FluxSource& source, VplImages& out,
              engine::GpuProfiler* profiler = nullptr) const;

 private:
  std::string passName_;
  engine::ComputeProgram program_;
  engine::Buffer albedoTable_;  // createGgxAlbedoTable: the specular flux's directional albedo
};

class ReflectiveShadowMap {
 public:
  ReflectiveShadowMap(engine::Context& ctx, uint32_t size);

  void record(VkCommandBuffer cmd, const engine::SceneGpu& scene, engine::Rasterizer& rasterizer,
              engine::GBufferResolve& resolve, const RsmView& view, const engine::Light& light,
              engine::GpuProfiler* profiler = nullptr);

  uint32_t size() const { return size_; }
  engine::GBuffer& surface() { return surface_; }  // the light's G-buffer (normals live here)
  VplImages& vpls() { return vpls_; }
  engine::Image& position() { return vpls_.position; }
  engine::Image& diffuseFlux() { return vpls_.diffuse; }
  engine::Image& specularFlux() { return vpls_.specular; }

 private:
  uint32_t size_;
  FluxPass flux_;
  engine::Buffer visibility_;
  engine::GBuffer surface_;
  VplImages vpls_;
};

}  // namespace gi
