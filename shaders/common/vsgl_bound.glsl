// A conservative upper bound of the light one VSGL lobe can give any receiver of a group
// (vsgl-math.md sections 4.1-4.4), for VSGL culling in vsgl_shade.comp (VSGL_SHADE_CULL). The
// derivation is in docs/techniques/vsgl-culling.md; the double twin is
// gi/src/reference/vsgl_bound.cpp. It bounds the exact integrals that the shading approximates:
//   diffuse  rho / pi integral L(w) (w . n)^+ dw,   glossy  integral L(w) f_spec(w) (w . n)^+ dw,
// L(w) = E G(w; -a, lambda_e) G(w; xi, d^2 / v') the lobe's incoming radiance (section 4.1),
// E = P / (2 pi S(lambda_e) v'), for every receiver position inside a sphere and every normal
// inside a cone. Visibility is bounded by 1.
#ifndef SHADERS_COMMON_VSGL_BOUND_GLSL
#define SHADERS_COMMON_VSGL_BOUND_GLSL

#include "sg.glsl"

// The spot's tail: outside the cone where G(w; xi, lambda_s) >= kVsglBoundTail the spot is
// bounded by the tail itself. ln(1e4): the directional bounds hold inside that cone, the rest
// of the spot's light is at most 1e-4 of the distance bound.
const float kVsglBoundTail = 1e-4;
const float kVsglBoundLogInverseTail = 9.2103404;
// Radians added to the cone: an fp32 angle between near-parallel unit vectors, acos of a dot
// product rounded to ~1e-7, is off by up to ~5e-4.
const float kVsglBoundAngleMargin = 1e-3;

// What the bound needs of a group of receivers.
struct VsglReceivers {
  vec3 centre;        // bounding sphere of the positions
  float radius;
  vec3 normalAxis;    // a cone holding every normal: unit axis ...
  float normalAngle;  // ... and half-angle, radians (pi: no cone)
  float albedo;       // largest diffuse albedo channel
  float fresnel;      // largest F0 channel or F90; 0 without the glossy term
  float alpha;        // smallest GGX alpha (floored at 1e-3 as brdf.glsl)
  float viewCosine;   // smallest n . v (clamped to 1e-4 as brdf.glsl)
  float specularAlbedo;  // largest directional albedo of the specular lobe (ggxSpecularAlbedo)
};

// The tabulated albedo is the shading's own constant-light limit; the SG fit may exceed it a
// little for light neither wide nor sharp (tests/unit/test_vsgl_bound.cpp measures this margin).
const float kVsglBoundAlbedoMargin = 1.1;

float vsglBoundAngle(vec3 a, vec3 b) {
  return acos(clamp(dot(a, b), -1.0, 1.0));
}

// (diffuse, glossy) bounds, in the units of the lobe's largest power channel, for a lobe with
// mean, variance, emission axis and sharpness, and logScale = log(P / (2 pi S(lambda_e))) (the
// shading's per-lobe constant). A lobe without power gives 0; overflow gives +inf, never NaN
// unless a factor is 0 times +inf (then no comparison skips it).
vec2 vsglLobeBound(vec3 mean, float variance, vec3 axis, float sharpness, float logScale,
                   VsglReceivers r) {
  vec3 toLight = mean - r.centre;
  float centreDistance = length(toLight);
  float nearest = max(centreDistance - r.radius, 0.0);  // d >= nearest for every receiver
  float nearest2 = nearest * nearest;
  // v' = max(v, d^2 2^-41, FLT_MIN) grows with d: its least value over the group.
  float variance0 = max(max(variance, nearest2 * kSgVarianceFloorScale), kSgFltMin);
  // The lobe's light integrated over directions, E S(lambda_s) = P (1 - e^(-2 d^2 / v')) /
  // (S(lambda_e) d^2) <= P / S(lambda_e) min(1 / d^2, 2 / v') (S <= 4 pi): the inverse-square
  // law, capped where the receiver is inside the spot.
  float scale = exp(logScale);
  float cap = 2.0 / variance0;
  float flux = 2.0 * kSgPi * scale * (nearest2 > 0.0 ? min(1.0 / nearest2, cap) : cap);
  float peak = scale / variance0;  // E, the largest incoming radiance

  // Directions: the spot's axis xi lies in the cone of the sphere seen from the mean, widened by
  // the spot's own spread (lambda_s = d^2 / v' >= nearest^2 / v'_0) down to the tail.
  // The tail's cone: 1 - cos = ln(1 / tail) / lambda_s, the whole sphere once that reaches 2.
  float spotSharpness = nearest2 / variance0;
  bool narrow = spotSharpness > 0.5 * kVsglBoundLogInverseTail;
  float coneAngle = centreDistance > r.radius ? asin(r.radius / centreDistance) : kSgPi;
  coneAngle += (narrow ? acos(1.0 - kVsglBoundLogInverseTail / spotSharpness) : kSgPi) +
               kVsglBoundAngleMargin;
  bool everywhere = coneAngle >= kSgPi;
  vec3 toward = centreDistance > 0.0 ? toLight / centreDistance : -axis;
  // The largest emission G(w; -a, lambda_e) and cosine (w . n)^+ over the cone.
  float emission = everywhere ? 1.0
      : exp(sharpness * (cos(max(vsglBoundAngle(toward, -axis) - coneAngle, 0.0)) - 1.0));
  float cosine = everywhere ? 1.0
      : max(cos(max(vsglBoundAngle(toward, r.normalAxis) - coneAngle - r.normalAngle, 0.0)), 0.0);
  float tail = everywhere ? 0.0 : kVsglBoundTail;

  float diffuse = flux * (r.albedo / kSgPi) * (emission * cosine + tail);
  // Glossy, the smaller of two bounds. Sharp light: f_spec (w . n) = D G2 F / (4 n.v) <= F D_max
  // G1(v) / (4 n.v) with D_max = 1 / (pi alpha^2) and G1(v) / (4 n.v) = 1 / (2 (n.v +
  // sqrt(alpha^2 + (1 - alpha^2) n.v^2))), least at the group's smallest alpha and n . v, over
  // the same directions. Wide light: the largest incoming radiance times the lobe's albedo.
  float a2 = r.alpha * r.alpha;
  float peakBrdf = r.fresnel / (2.0 * kSgPi * a2 *
      (r.viewCosine + sqrt(a2 + (1.0 - a2) * r.viewCosine * r.viewCosine)));
  float above = cosine > 0.0 ? 1.0 : 0.0;
  float sharpGlossy = flux * (emission * above + tail) * peakBrdf;
  float wideGlossy = peak * max(emission, tail) * r.specularAlbedo * kVsglBoundAlbedoMargin;
  float glossy = min(sharpGlossy, wideGlossy);
  return vec2(diffuse, glossy);
}

#endif
