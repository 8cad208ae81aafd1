// Planar emitters (docs/techniques/planar-emitters.md): the emission model of a VSGL's two lobes,
// in double, the twin of shaders/common/vsgl_emitter.glsl. A flat cluster is a Lambertian (or
// glossy) patch of a plane: it sends no light below that plane, none along it, and is seen
// foreshortened. A cluster that is not flat (a corner, a thin wall lit from both sides) keeps the
// SG emitter of vsgl-math.md section 3.4. The blend between the two follows the diffuse lobe's
// sharpness continuously, so no threshold can flicker.
#pragma once

#include "reference/sg_math.h"
#include "shared/vsgl.h"

namespace gi {

// beta in [0, 1]: 0 at or below VSGL_CORNER_SHARPNESS, 1 at VSGL_FLAT_SHARPNESS, smoothstep
// between.
double vsglPlanarity(double diffuseSharpness);

// The emission of each lobe of `vsgl`; `planar` false (Settings::planarEmitters off) gives the
// SG emitter for both. The plane normal is the diffuse lobe's axis (the cluster's mean normal);
// a VSGL without diffuse weight has no plane and keeps the SG emitter. The diffuse lobe is the
// Lambertian one (its sharpness follows the spot); the specular lobe keeps its sharpness, cut
// by the same cosine factor, with N = vsglSpecularNormalisation at (xi . n)^+ (a lobe below the
// plane, which no reflection makes, loses what the cut removes instead of being amplified).
struct VsglEmission {
  VsglLobeEmission diffuse;
  VsglLobeEmission specular;
};
VsglEmission vsglEmission(const gpu::Vsgl& vsgl, bool planar);

// N = integral over the sphere of G(w; axis, lambda) ((1 - beta) + beta (w . n)^+)
//   = (1 - beta) S(lambda) + beta pi D(lambda, axis . n), D the [T24] clamped-cosine integral.
double vsglSpecularNormalisation(double sharpness, double axisDotNormal, double planarity);

// N of a Lambertian lobe at emission sharpness lambda_e: (1 - beta) S(lambda_e) + 2 pi beta
// U(lambda_e), the exact integral of G(w; n, lambda_e) ((1 - beta) + beta (w . n)^+).
double vsglLambertianNormalisation(double emissionSharpness, double planarity);

}  // namespace gi
