// How a light's reflective shadow map sees it (the views, their texel areas and solid angles, the
// flux's source), shared by the RSM pass (passes/rsm.h) and the CPU twins (reference/): CPU-side
// geometry only, no GPU work.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "engine/rasterizer.h"
#include "engine/scene.h"
#include "engine/view.h"

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

}  // namespace gi
