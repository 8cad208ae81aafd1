// CPU twin of rsm_flux.comp, in double. It takes the light's G-buffer decoded from the GPU (so
// both sides start from the same depth and material values) and the RsmView, and recomputes
// each texel's position relative to the light and its flux. The surface itself (depth, normal,
// materials) is checked by the G-buffer resolve's own reference.
#pragma once

#include <vector>

#include "engine/gbuffer_reference.h"
#include "common/rsm_view.h"

namespace gi {

struct RsmTexelReference {
  glm::dvec3 offset{0.0};        // VPL position minus RsmView::origin (0 when unlit)
  double lit = 0.0;              // 1 when the texel carries power
  glm::dvec3 incident{0.0};      // Phi_in per channel, W
  glm::dvec3 diffuseFlux{0.0};   // albedo * Phi_in
  glm::dvec3 specularFlux{0.0};  // F0 * Phi_in
  double roughness = 0.0;        // perceptual (0 when unlit)
};

// Rec. 709 luminance, the scalar weight of RGB powers (shaders/common/color.glsl).
double luminance709(const glm::dvec3& c);

std::vector<RsmTexelReference> rsmFluxReference(const engine::GBufferData& surface,
                                                const RsmView& view, const FluxSource& source);

// Sum over all texels of the texel solid angle A cos^3(theta) of a square perspective RSM with
// `size` texels a side and half angle `halfAngle` (midpoint rule of the frustum's solid angle).
double rsmSolidAngleSum(uint32_t size, double halfAngle);

}  // namespace gi
