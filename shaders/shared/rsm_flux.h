// Reflective shadow map (Dachsbacher & Stamminger 2005) flux pass: turns the G-buffer rendered
// from the light into virtual point lights. Per texel (vsgl-math.md section 2):
//   incident flux  Phi_in = I(theta) * A * cos^3(theta)   (spot; A = texel area on the plane at
//                  unit distance, cos^3 = solid-angle Jacobian of that plane)
//                  Phi_in = E * texel area                (directional, orthographic RSM)
//                  a spot with a range r also carries KHR_lights_punctual's window
//                  clamp(1 - (d / r)^4, 0, 1) at the texel's distance d, as its direct light
//   reflected flux Phi_d = albedo * Phi_in,  Phi_s = A(n . l) * Phi_in, A the specular lobe's
//                  directional albedo F90 A0 + F0 (A1 - A0) from the GGX table of
//                  common/sg_lighting.glsl at the light's incidence (Fresnel and masking in it)
// Images written (all R32G32B32A32_SFLOAT):
//   position  xyz = VPL position minus the RSM origin (the light position, or the eye of the
//             directional light's orthographic view), w = 1 for a VPL with power, else 0
//   diffuse   rgb = Phi_d (W), a = Phi_in (W)
//   specular  rgb = Phi_s (W), a = perceptual roughness
// The normal stays in the light G-buffer (RG16_SNORM octahedral). Texels on background or
// outside the spot cone carry zero power and w = 0.
#ifndef SHADERS_SHARED_RSM_FLUX_H
#define SHADERS_SHARED_RSM_FLUX_H
#include "interop.h"

#define RSM_GROUP_X 8
#define RSM_GROUP_Y 8

SHARED_BEGIN

struct RsmFluxPush {
  mat4 invViewProjRelative;  // inverse of (projection * light rotation): NDC -> offset from origin
  vec4 axis;                 // xyz unit direction the light travels (view axis), w unused
  vec4 radiance;             // rgb = colour * intensity: W/sr (spot) or W/m^2 (directional)
  vec4 spot;                 // x = angle scale, y = angle offset (KHR falloff), z = texel area A
                             // (spot: on the unit-distance plane; directional: m^2), w = range
                             // in metres (spot; 0 = none)
  uvec2 size;                // RSM texels
  uint perspective;          // 1 = spot (perspective RSM), 0 = directional (orthographic)
  uint pad;
};

SHARED_END

SHARED_ASSERT_SIZE(RsmFluxPush, 128);
#endif
