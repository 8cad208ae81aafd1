// The reflective shadow map of one light: the G-buffer resolve rendered from the light (same
// rasterizer, same surface code as the camera) followed by rsm_flux.comp, which turns every
// texel into a virtual point light with a position relative to the light and its flux
// (formats: shaders/shared/rsm_flux.h).
#pragma once

#include "engine/gbuffer.h"
#include "engine/rasterizer.h"
#include "engine/scene.h"

namespace gi {

// How the RSM sees its light. Spot lights: a square perspective frustum whose half angle is the
// outer cone (corner texels outside the cone get zero power); directional lights: an
// orthographic view enclosing the scene. Point lights need six views and are not supported yet.
struct RsmView {
  engine::View view;                  // world -> clip for the rasterizer; width = height = size
  glm::mat4 invViewProjRelative{1.0f};  // NDC -> offset from `origin` (no translation inside)
  glm::vec3 origin{0.0f};             // light position (spot) or orthographic eye (directional)
  glm::vec3 axis{0.0f, 0.0f, -1.0f};  // unit direction the light travels
  bool perspective = true;
  float tanHalfAngle = 0.0f;          // spot: tan of the frustum's half angle
  float texelArea = 0.0f;             // spot: on the unit-distance plane; directional: m^2
};

// Throws engine::Error for point lights and for spots wider than kMaxRsmHalfAngle.
RsmView makeRsmView(const engine::Scene& scene, const engine::Light& light, uint32_t size);

// A single perspective view cannot hold a cone much wider than this (texel density at its rim
// falls as cos^3); wider spot lights are refused rather than sampled badly.
constexpr float kMaxRsmHalfAngle = 1.3f;

// Exact solid angle of the square frustum with half angle `halfAngle` on both axes:
// 4 asin(sin^2 halfAngle) (vsgl-math.md section 2).
double frustumSolidAngle(double halfAngle);

class ReflectiveShadowMap {
 public:
  ReflectiveShadowMap(engine::Context& ctx, uint32_t size);

  void record(VkCommandBuffer cmd, const engine::SceneGpu& scene, engine::Rasterizer& rasterizer,
              engine::GBufferResolve& resolve, const RsmView& view, const engine::Light& light,
              engine::GpuProfiler* profiler = nullptr);

  uint32_t size() const { return size_; }
  engine::GBuffer& surface() { return surface_; }  // the light's G-buffer (normals live here)
  engine::Image& position() { return position_; }
  engine::Image& diffuseFlux() { return diffuse_; }
  engine::Image& specularFlux() { return specular_; }

 private:
  uint32_t size_;
  engine::ComputeProgram flux_;
  engine::Buffer visibility_;
  engine::GBuffer surface_;
  engine::Image position_;
  engine::Image diffuse_;
  engine::Image specular_;
};

}  // namespace gi
