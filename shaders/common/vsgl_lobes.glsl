// Per-VPL lobe encodings for the summable VSGL axes (vsgl-math.md section 3.3).
#ifndef SHADERS_COMMON_VSGL_LOBES_GLSL
#define SHADERS_COMMON_VSGL_LOBES_GLSL

#include "shared/vsgl.h"

// Inverse of Banerjee's vMF sharpness estimate kappa(r) = r (3 - r^2) / (1 - r^2): the mean
// length r in [0, 1) whose estimate is `sharpness`, so a one-VPL cluster reproduces its own
// sharpness. Below 64 the trigonometric closed form of the cubic (Peters 2016, via Tokuyoshi's
// VSGL code), then one Newton step on r (3 - r^2) - lambda (1 - r^2) = 0 written with
// q = 1 - r^2 = s (2 - s), s = 1 - r, so that it does not cancel: the closed form's last sum
// cancels a factor ~lambda / 3, and alone it was 1.7e-5 off at lambda = 63.9 on lavapipe, its
// round trip 0.1 % (tests/gpu/test_stability_sg.cpp). Above 64 it cancels outright (r ~ 1 - 1 /
// lambda), so the expansion 1 - r = 1 / ((lambda - 1/2) (1 + 1.25 / lambda^2)), accurate to
// O(lambda^-4) (< 1e-7 there).
float banerjeeMeanLength(float sharpness) {
  if (sharpness <= 0.0) return 0.0;
  if (sharpness > 64.0) return 1.0 - 1.0 / ((sharpness - 0.5) * (1.0 + 1.25 / (sharpness * sharpness)));
  float a = sharpness / 3.0;
  float a2 = a * a;
  float phi = atan(sqrt(1.0 + 3.0 * a2 * (1.0 + a2)), a2 * a) / 3.0;
  float r = sqrt(1.0 + a2) * (sqrt(3.0) * sin(phi) - cos(phi)) + a;
  float s = 1.0 - r;
  float q = s * (2.0 - s);
  return r - (r * (2.0 + q) - sharpness * q) / (3.0 * q + 2.0 * sharpness * r);
}

// The reflection lobe of light arriving from `toLight` at a GGX surface (normal n, perceptual
// roughness r, alpha = max(r^2, kMinAlpha) as brdf.glsl): the NDF as an SG of sharpness
// 2 / alpha^2 - 2 (Tokuyoshi & Harada 2019), centred on the dominant visible normal h (centre
// of the VNDF's spherical cap, Dupuy & Benyoub 2023) and warped to reflection directions:
// axis = reflect(-toLight, h), sharpness * h.n / (4 |toLight . h|).
void vplSpecularLobe(vec3 n, vec3 toLight, float roughness, out vec3 axis, out float sharpness) {
  float alpha = max(roughness * roughness, 1e-3);
  float alpha2 = alpha * alpha;
  float wz = dot(toLight, n);
  vec3 wxy = toLight - wz * n;
  float wxy2 = dot(wxy, wxy);
  float t = sqrt(alpha2 * wxy2 + wz * wz);
  // For light below the horizon (wz < 0) t + wz cancels; the identity below does not.
  float z = wz >= 0.0 ? t + wz : alpha2 * wxy2 / (t - wz);
  vec3 h = alpha2 * wxy + z * n;
  float hLength = length(h);
  h = hLength > 0.0 ? h / hLength : n;
  axis = reflect(-toLight, h);
  float lambdaH = 2.0 / alpha2 - 2.0;
  sharpness = lambdaH * max(dot(h, n), 0.0) / max(4.0 * abs(dot(toLight, h)), 1e-8);
}

// The share of a VPL's glossy lobe that the VSGL's glossy lobe carries; the rest joins the
// diffuse lobe. A cluster's lobe is one SG, so a mirror's narrow reflections and a rough
// surface's broad ones mixed in one kernel (a checker of polished and matte tiles) make one lobe
// of middling sharpness that sends the mirror's light where no mirror does; a reflection no
// narrower than the Lambert lobe is emitted as the Lambert lobe instead. Smoothstep in log
// sharpness from VSGL_FLAT_SHARPNESS (0) to VSGL_GLOSSY_SHARPNESS_RATIO times it (1).
float vplGlossyShare(float sharpness) {
  float x = log(max(sharpness, 1e-30) / float(VSGL_FLAT_SHARPNESS)) /
            log(float(VSGL_GLOSSY_SHARPNESS_RATIO));
  return smoothstep(0.0, 1.0, x);
}

// Banerjee's vMF sharpness estimate from a mean resultant length r (section 3.3),
// r (3 - r^2) / (1 - r^2), clamped to VSGL_MAX_SHARPNESS (r -> 1: one VPL or identical axes).
float banerjeeSharpness(float r) {
  if (!(r > 0.0)) return 0.0;
  if (r >= 1.0) return float(VSGL_MAX_SHARPNESS);
  return min(r * (3.0 - r * r) / ((1.0 - r) * (1.0 + r)), float(VSGL_MAX_SHARPNESS));
}

// A cluster lobe's SG from its weighted mean axis vector (axis sums / weight): unit axis and
// Banerjee sharpness; a zero mean axis (opposite lobes cancelled) is isotropic about +z.
void lobeFromMeanAxis(vec3 meanAxis, out vec3 axis, out float sharpness) {
  float meanLength = length(meanAxis);
  axis = meanLength > 0.0 ? meanAxis / meanLength : vec3(0.0, 0.0, 1.0);
  sharpness = banerjeeSharpness(meanLength);
}

// Planar emitters' beta (common/vsgl_emitter.glsl), read from a diffuse lobe's sharpness:
// smoothstep from VSGL_CORNER_SHARPNESS (0) to VSGL_FLAT_SHARPNESS (1). Here because generation
// reads it too (kernels that leave their surface).
float vsglPlanarity(float diffuseSharpness) {
  return smoothstep(float(VSGL_CORNER_SHARPNESS), float(VSGL_FLAT_SHARPNESS), diffuseSharpness);
}

// A VSGL lobe from its cluster sums (vsgl-math.md 3.2), for filtered kernels and k-means
// clusters alike: mean (relative to the RSM origin, moved to world by `origin`), per-axis
// variance (never negative), axis and Banerjee sharpness (axis length 0 -> isotropic), power.
// No weight (w = 0) gives a powerless lobe at the origin.
VsglLobe buildVsglLobe(vec4 power, vec4 position, vec4 axis, vec3 origin) {
  VsglLobe lobe;
  float w = power.w;
  if (!(w > 0.0)) {
    lobe.meanVariance = vec4(origin, 0.0);
    lobe.axisSharpness = vec4(0.0, 0.0, 1.0, 0.0);
    lobe.power = vec4(0.0);
    return lobe;
  }
  vec3 mean = position.xyz / w;
  float variance = max(0.0, position.w / w - dot(mean, mean)) * 0.5;
  vec3 unitAxis;
  float sharpness;
  lobeFromMeanAxis(axis.xyz / w, unitAxis, sharpness);
  lobe.meanVariance = vec4(origin + mean, variance);
  lobe.axisSharpness = vec4(unitAxis, sharpness);
  lobe.power = power;
  return lobe;
}

#endif
