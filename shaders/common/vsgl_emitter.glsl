// Planar emitters (docs/techniques/planar-emitters.md) in fp32: the emission of a VSGL's two
// lobes. The double twin is gi/src/reference/vsgl_emitter.cpp; names follow it. A flat cluster
// sends no light below or along its plane and is seen foreshortened: the radiant intensity is
//   I(w) = Phi G(w; xi, lambda_e) ((1 - beta) + beta (w . n)^+) / N,
// the spot's variance is f v with the same factor f at the receiver's direction from the mean
// (common/sg.glsl vsglSpot), and beta (planarity) runs smoothly from 0 (a corner) to 1 (flat)
// with the diffuse lobe's sharpness. Include after the prerequisites of common/sg_lighting.glsl.
#ifndef SHADERS_COMMON_VSGL_EMITTER_GLSL
#define SHADERS_COMMON_VSGL_EMITTER_GLSL

#include "shared/vsgl.h"
#include "sg_lighting.glsl"
#include "vsgl_lobes.glsl"  // vsglPlanarity

// The planarity of a VSGL's emitter: beta of its diffuse lobe, 0 (the SG emitter) when `planar`
// is off or the VSGL has no diffuse weight or axis.
float vsglEmitterPlanarity(Vsgl vsgl, bool planar) {
  vec3 axis = vsgl.diffuse.axisSharpness.xyz;
  bool hasPlane = planar && vsgl.diffuse.power.a > 0.0 && dot(axis, axis) > 0.0;
  return hasPlane ? vsglPlanarity(vsgl.diffuse.axisSharpness.w) : 0.0;
}

// The plane as vsglSpot takes it, (beta n, 1 - beta), from the planarity and the diffuse lobe's
// axis (n, the cluster's mean normal, is that axis normalised); (0, 0, 0, 1) for beta = 0.
// Shading broadcasts beta and the axis and rebuilds the plane here (common/ism_broadcast.glsl
// says why).
vec4 vsglEmitterPlane(vec3 diffuseAxis, float beta) {
  return beta > 0.0 ? vec4(beta * normalize(diffuseAxis), 1.0 - beta) : vec4(0.0, 0.0, 0.0, 1.0);
}

// N of a specular lobe: (1 - beta) S(lambda) + beta pi D(lambda, (xi . n)^+), D the [T24]
// clamped-cosine integral. Per lobe: the specular lobe keeps its sharpness. A reflection leaves
// above its surface; a lobe whose axis points below the plane (no RSM makes one) is normalised as
// if it lay along the horizon, so that it loses what the cut removes instead of being amplified
// by 1 / D, which has no floor (and no fp32 accuracy) there.
float vsglSpecularNormalisation(VsglLobe lobe, vec4 plane) {
  float beta = 1.0 - plane.w;
  float sharpness = lobe.axisSharpness.w;
  float axisDotNormal = beta > 0.0 ? max(dot(lobe.axisSharpness.xyz, plane.xyz) / beta, 0.0) : 0.0;
  return plane.w * sgIntegral(sharpness) +
         beta * kSgPi * sgClampedCosineIntegralOverPi(sharpness, axisDotNormal);
}

// The diffuse lobe fits the Lambert lobe. Seen from afar (a sharp spot) a flat cluster's
// emission is the exact cosine, which the foreshortening alone gives, so its SG fades:
//   lambda_e = (1 - beta) lambda + beta lambda^2 / (lambda + lambda_s),
// lambda_s the spot's sharpness. Near the cluster (a wide spot) lambda_e -> lambda keeps the
// light leaving the surface's front; N = (1 - beta) S(lambda_e) + 2 pi beta U(lambda_e) (the
// cosine-weighted integral about the axis, exact) keeps the power at every distance.
float vsglLambertianSharpness(float sharpness, float spotSharpness, vec4 plane) {
  float beta = 1.0 - plane.w;
  return plane.w * sharpness +
         beta * sharpness * sharpness / max(sharpness + spotSharpness, kSgFltMin);
}

float vsglLambertianNormalisation(float emissionSharpness, vec4 plane) {
  return plane.w * sgIntegral(emissionSharpness) +
         (1.0 - plane.w) * 2.0 * kSgPi * clampedCosineUpperIntegral(emissionSharpness);
}

// Near a flat cluster (a wide spot) its light comes from below its plane, which the emission SG
// bounds only softly: a receiver facing the way the cluster faces would still see the SG's tail
// (4.9 % of the exitance at lambda = 2.29, where the truth is 0). The light of such receivers is
// scaled by keep = 1 - beta w (n . n_r)^+, w = lambda / (lambda + lambda_s) the spot's nearness
// (1 inside the cluster, 0 far away, where the sharp spot already lies at the horizon).
float vsglCoplanarKeep(float sharpness, float spotSharpness, vec4 plane, vec3 normal) {
  float near = sharpness / max(sharpness + spotSharpness, kSgFltMin);
  return 1.0 - near * max(dot(plane.xyz, normal), 0.0);
}

// Incoming radiance at `receiver` (unit normal `normal`) from a diffuse lobe under `plane`.
// logPower = log(power / (2 pi)): N depends on the receiver here.
Sg vsglLambertianRadiance(vec3 mean, float variance, vec3 axis, float sharpness, float logPower,
                          vec3 receiver, vec3 normal, vec4 plane) {
  Sg spot = vsglSpot(mean, variance, receiver, plane, -axis);
  float emission = vsglLambertianSharpness(sharpness, spot.sharpness, plane);
  Sg radiance = sgProduct(Sg(-axis, emission, 0.0), spot);
  float keep = vsglCoplanarKeep(sharpness, spot.sharpness, plane, normal);
  radiance.logAmplitude +=
      keep > 0.0 ? logPower + log(keep / vsglLambertianNormalisation(emission, plane)) : -1.0 / 0.0;
  return radiance;
}

#endif
