// CPU twin of the direct lighting pass (shaders/lighting/direct_light.comp): the same BRDF
// (Lambert + GGX with height-correlated Smith visibility + Schlick Fresnel, common/brdf.glsl),
// inverse-square falloff with KHR_lights_punctual's range window and spot cone falloff, and
// the same normal-offset 3x3 PCF of the shadow maps, evaluated in double.
//
// Inputs are identical (the GPU's decoded G-buffer, the same LightSetup and shadow maps), but
// the GPU evaluates in fp32, and three of its steps are ill-conditioned: the receiver rebuilt
// from depth with the inverse view-projection (h = M (x, y, z, 1) cancels terms of size
// |eye| / znear down to size 1 / distance), the view ray from two nearby unprojected points,
// and GGX's D near the peak of a glossy lobe. The reference bounds the first two errors by
// forward error analysis (Higham's gamma_n) and re-evaluates the shading across that box of
// receivers and view vectors, and bounds the third from D's derivative; `errorBound` is the
// sum, a first-order bound of how far a correct fp32 evaluation may be from the double one
// beyond a few ulps of rounding. Shadow tests are discontinuous: a pixel whose PCF result
// changes within the box, or one of whose taps is within fp32 rounding of its depth threshold
// or texel border, is flagged `ambiguous`, since one flipped tap moves the result by a ninth
// of a light and no tolerance on values can absorb that.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "engine/direct_light.h"
#include "engine/gbuffer_reference.h"
#include "engine/view.h"

namespace engine {

struct DirectLightReference {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::dvec3> radiance;  // W sr^-1 m^-2, 0 on background, row 0 at the top
  std::vector<double> errorBound;    // per pixel, any channel (see above)
  std::vector<uint8_t> ambiguous;    // 1 where the shadow result is undecidable in fp32
};

// What a light delivers at point p, without visibility: the unit direction to the light, its
// distance (0 for a directional light, which has none) and the irradiance on a surface facing
// it (W/m^2; times n . l for any other surface). Inverse-square falloff with
// KHR_lights_punctual's range window and smooth spot cone, as direct_light.comp.
struct LightIncidence {
  glm::dvec3 toLight{0.0};
  double distance = 0.0;
  glm::dvec3 irradiance{0.0};
};
LightIncidence lightIncidence(const gpu::GpuLight& light, glm::dvec3 p);

// The shadow maps of every view in `setup`, rendered by rasterizeReference and laid out as the
// GPU's buffer: resolution^2 visibility texels per view, views back to back.
std::vector<uint64_t> shadowMapsReference(const Scene& scene, const LightSetup& setup,
                                          uint32_t resolution);

// Radiance of every G-buffer pixel lit by setup.lights; `shadowMaps` holds the views of
// setup.views as shadowMapsReference lays them out (may be empty when no light has views).
DirectLightReference directLightReference(const GBufferData& gbuffer, const View& view,
                                          const LightSetup& setup, uint32_t shadowResolution,
                                          std::span<const uint64_t> shadowMaps);

}  // namespace engine
