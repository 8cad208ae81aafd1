// Spherical Gaussian (SG) math for VSGL shading (vsgl-math.md section 4), in double and naive on
// purpose but with the stable forms of section 4.2: the oracle that the GLSL SG functions are
// tested against.
//
// This work is based on:
//   [T22] Tokuyoshi, "Accurate Diffuse Lighting from Spherical Gaussian Lights", 2022, Eq. 1
//         (the hemispherical-integral interpolation, as implemented in [R]).
//   [T24] Tokuyoshi et al., "Hierarchical Light Sampling with Accurate Spherical Gaussian
//         Lighting", 2024, supplementary document Listings 4-7 (vMF hemisphere fraction, SG x
//         clamped cosine, as implemented in [R]).
//   [R]   github yusuketokuyoshi/VSGL (stable SG product, em1x, the VSGL radiance SG).
//   [TS06] Tsai and Shih, "All-Frequency Precomputed Radiance Transfer using Spherical Radial
//         Basis Functions and Clustered Tensor Approximation", SIGGRAPH 2006 (SG inner product).
//
// Conventions. G(w; xi, lambda) = exp(lambda (w . xi - 1)): unit peak, unit axis xi, sharpness
// lambda >= 0. Every "per 2 pi" integral below is the integral divided by 2 pi, every "over pi"
// one divided by pi, as in section 4.
#pragma once

#include <glm/glm.hpp>

#include "common/ggx_albedo.h"
#include "shared/vsgl.h"

namespace gi {

// (e^x - 1) / x, 1 at x = 0 (section 4.2). In double, expm1 is accurate near 0, so the
// Higham/Kahan trick that [R] needs in fp32 is unnecessary here.
double em1x(double x);

// S(lambda) = integral of G over the sphere = 2 pi (1 - e^(-2 lambda)) / lambda, written as
// 4 pi em1x(-2 lambda) (section 4.2) so that lambda -> 0 gives 4 pi instead of 0 / 0.
double sgIntegral(double lambda);

// G(omega; axis, lambda) as exp(-lambda / 2 |omega - axis|^2) (section 4.2): equal to
// exp(lambda (omega . axis - 1)) for unit vectors, but 1 - cos is not rounded away near the peak.
double sgEvaluate(glm::dvec3 omega, glm::dvec3 axis, double lambda);

// exp(logAmplitude) G(w; axis, sharpness). The amplitude is kept as a logarithm because the
// products below have amplitudes down to e^(-2^42).
struct Sg {
  glm::dvec3 axis{0.0, 0.0, 1.0};  // unit
  double sharpness = 0.0;
  double logAmplitude = 0.0;
};

double sgEvaluate(const Sg& sg, glm::dvec3 omega);

// The product of two SGs is an SG (section 4.2): u = l1 xi1 + l2 xi2, sharpness |u|, axis
// u / |u|, log amplitude la1 + la2 + (|u| - l1 - l2) in the cancellation-free form
// -l1 l2 |xi1 - xi2|^2 / (|u| + l1 + l2) (0 when every sharpness is 0). |u| = 0 (opposite axes
// with equal sharpness, or both sharpnesses 0) gives a.axis: any unit axis is exact there.
Sg sgProduct(const Sg& a, const Sg& b);

// Integral of the product over the sphere, e^(l_p) S(lambda_p) (section 4.2, [TS06]).
double sgInnerProduct(const Sg& a, const Sg& b);

// Integral of G(w; n, lambda) over the hemisphere w . n > 0, per 2 pi: em1x(-lambda) (section
// 4.2, exact).
double sgUpperHemisphericalIntegral(double lambda);
// The same for G(w; -n, lambda): e^(-lambda) em1x(-lambda) (exact).
double sgLowerHemisphericalIntegral(double lambda);
// [T22] interpolation factor between the two for an axis with xi . n = cosine (section 4.2):
// s = 1/2 + 1/2 erf(tau c) / erf(tau), tau = lambda sqrt((lambda/2 + A) / ((lambda + B) lambda
// + C)); s = (1 + c) / 2 in the limit lambda -> 0. Exact at c = +-1.
double sgHemisphericalLerpFactor(double lambda, double cosine);
// Integral of G(w; xi, lambda) over w . n > 0 per 2 pi, with xi . n = cosine ([T22] fit,
// section 4.2): H_low + s (H_up - H_low). Measured in fp64 against quadrature over
// lambda in [0.1, 50]: |error| <= 0.5 % of H_up (worst 0.49 % at lambda = 7.7, c = 0.66; the
// 0.4 % quoted in vsgl-math.md is slightly optimistic). GLSL test tolerances start from this.
double sgHemisphericalIntegral(double lambda, double cosine);
// The fraction of a vMF (normalised SG) that lies in w . n > 0 (section 4.2):
// (e^(-lambda) + s (1 - e^(-lambda))) / (1 + e^(-lambda)).
double vmfUpperHemisphereFraction(double lambda, double cosine);

// Integrals of G(w; n, lambda) (w . n)^+ (upper, axis n) and of G(w; -n, lambda) (w . n)^+
// (lower, axis -n), per 2 pi (section 4.3 option 2, [T24]):
//   U = (1 - em1x(-lambda)) / lambda,  L = e^(-lambda) (em1x(-lambda) - e^(-lambda)) / lambda,
// by their Taylor series for lambda <= 0.5 where the closed forms cancel.
double clampedCosineUpperIntegral(double lambda);
double clampedCosineLowerIntegral(double lambda);
// D(lambda, c) = (1/pi) integral of G(w; xi, lambda) (w . n)^+ dw with xi . n = cosine ([T24],
// section 4.3 option 2): 2 (L + (U - L) s), s the [T24] factor clamped to [0, 1]. The factor 2
// turns the per-2 pi U and L into "over pi", so D = 1 for lambda = 0 (any c): a white furnace,
// since (1/pi) integral of (w . n)^+ is 1. Fit error in fp64 (tests/unit/test_sg_math.cpp):
// <= 1.6e-3 of the front-facing value 2 U for every lambda and c; relative <= 2.5e-5 for
// lambda <= 0.5 and <= 6.5e-3 for c >= 0; unbounded relative error for back-facing lobes (the
// fit interpolates between L and U, so its error scales with U, not with D).
double sgClampedCosineIntegralOverPi(double lambda, double cosine);

// Positional-variance floor relative to the squared distance, v >= d^2 / 2^41 ([R], section
// 4.1): keeps lambda_x = d^2 / v <= 2^41 for zero-variance (single-texel) VSGLs, the same cap as
// VSGL_MAX_SHARPNESS.
inline constexpr double kVarianceFloorScale = 0x1p-41;
// Absolute variance floor (FLT_MIN): with d = 0 and v = 0 (a zero-variance VSGL exactly at the
// receiver, section 12 case 12) the radiance is a genuine point singularity; the floor makes it
// huge but finite instead of 0 / 0, and FLT_MIN is the floor the fp32 shader can use as well.
inline constexpr double kMinVariance = 0x1p-126;

// Incoming radiance at a receiver from one VSGL lobe (section 4.1; the record of section 3.4):
//   L_i(w) = scale G(w; -xi, lambda) G(w; l / d, lambda_x) = scale exp(sg.logAmplitude)
//            G(w; sg.axis, sg.sharpness),
// with l = mu - x, d = |l|, lambda_x = d^2 / v', scale E = Phi / (2 pi v' S(lambda)) and the
// clamped variance v' = max(v, d^2 / 2^41, 2^-126). Incident directions w point FROM the
// receiver TO the light, and xi is the direction light leaves the VSGL, hence -xi.
struct VsglIncomingRadiance {
  Sg sg;
  glm::dvec3 scale{0.0};  // E (RGB)
};
VsglIncomingRadiance vsglIncomingRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver);

// How a lobe's light leaves its cluster (docs/techniques/planar-emitters.md; built by
// vsgl_emitter.h). The radiant intensity toward direction w is
//   I(w) = Phi G(w; xi, lambda_e) ((1 - beta) + beta (w . n)^+) / N
// and the positional Gaussian is foreshortened by the same factor f = (1 - beta) + beta c, with
// c = (n . (x - mu))^+ / sqrt(d^2 + v) the receiver's elevation (w . n far away, regular at the
// mean): the spot's variance is f v. A Lambertian (diffuse)
// lobe's emission sharpness follows the spot's sharpness lambda_s,
//   lambda_e = (1 - beta) lambda + beta lambda^2 / (lambda + lambda_s),
// with N = (1 - beta) S(lambda_e) + 2 pi beta U(lambda_e); any other lobe keeps lambda_e = lambda
// and `normalisation`. The default is the SG emitter of section 3.4: beta = 0 and S(lambda).
struct VsglLobeEmission {
  double normalisation = -1.0;  // N of a non-Lambertian lobe; < 0: S(lambda)
  glm::dvec3 plane{0.0};        // beta n
  double flatness = 1.0;        // 1 - beta
  bool lambertian = false;
};
// The incoming radiance of a lobe with that emission: I(-w_l) / d^2 in the far field (w_l the
// unit direction from the receiver to the mean), E G(w; -xi, lambda_e) G(w; l / d, d^2 / v_f)
// with v_f = max(f v, d^2 / 2^41, 2^-126) and E = Phi f / (2 pi v_f N); 0 where f = 0.
// A Lambertian lobe also scales the light of a receiver with unit normal `normal` by
// keep = 1 - beta w (n . normal)^+, w = lambda / (lambda + lambda_s): near a flat cluster its
// light comes from below its plane, which a receiver facing the cluster's way cannot see.
VsglIncomingRadiance vsglIncomingRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver,
                                          const VsglLobeEmission& emission, glm::dvec3 normal);

// Outgoing diffuse radiance at a receiver with unit normal n and albedo rho from one VSGL lobe
// (section 4.3): rho E e^(l_p) D(lambda_p, xi_p . n), i.e. rho / pi times the integral of
// L_i (w . n)^+. No visibility.
glm::dvec3 vsglDiffuseRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver, glm::dvec3 normal,
                               glm::dvec3 albedo);

// ---------------------------------------------------------------------------------------------
// Glossy: SG light x the GGX specular lobe of shaders/common/brdf.glsl (section 4.4), ported to
// fp32 in shaders/common/sg_lighting.glsl with the same structure. Derivation, measured errors and
// bad regimes: docs/techniques/sg-lighting.md ("Glossy").

// alpha = roughness^2 is floored here as brdf.glsl floors it, and n . v as brdf.glsl clamps it.
constexpr double kSgGgxMinAlpha = 1e-3;
constexpr double kSgGgxMinViewCosine = 1e-4;

// (1 + beta) (1 - beta e^beta E1(beta)): the ratio between the exact peak of a 2-D Student-t
// lobe of scale a (the small-angle GGX reflection lobe) convolved with a Gaussian of variance
// a^2 / (2 beta) and the peak 1 / (1 + beta) that adding the two lobes' variances predicts. 1 at
// beta = 0 and beta -> infinity, 0.804 at its minimum (beta = 0.72). E1 from Abramowitz and Stegun
// 5.1.53 (beta <= 1, |error| < 2e-7) and 5.1.54 (beta > 1, |error| < 2e-8), the asymptotic series
// above beta = 100; relative error 1.9e-6 (tests/unit/test_sg_math.cpp). beta = +inf gives 1.
double sgGgxPeakCorrection(double beta);

// Directional albedo of brdf.glsl's specular lobe, integral of f_spec(w, v) (w . n)^+ dw, with
// f0 = 0 (x) and f0 = 1 (y); with Schlick's Fresnel the albedo at any f0 is x + f0 (y - x). A
// 17 x 17 table over (sqrt(n . v), sqrt(alpha)) computed by quadrature (the unit test
// re-derives its nodes), read bilinearly. nv and alpha are clamped like brdf.glsl.
glm::dvec2 ggxSpecularAlbedo(double nv, double alpha);

// Approximation of integral G(w; light.axis, light.sharpness) f_spec(w, view) (w . n)^+ dw for a
// UNIT-amplitude SG (light.logAmplitude is ignored: the caller multiplies by exp(logAmplitude)
// and the light's scale), f_spec exactly the specular BRDF of brdf.glsl: GGX NDF with alpha
// (floored at kSgGgxMinAlpha), height-correlated Smith visibility, Schlick Fresnel with f0 (RGB).
// normal and view are unit; view points from the surface to the viewer, and n . v is clamped to
// kSgGgxMinViewCosine as in brdf.glsl. Factorised as K E with
//   K = integral G p (the light's mass seen through the normalised reflection pdf p of the
//       symmetric GGX VNDF, [T24] Section 5.2), a blend of [T24]'s NDF filtering (exact for sharp
//       lights) and the inner product with a normalised reflection SG (exact for wide ones),
//       scaled by sgGgxPeakCorrection;
//   E = the mean of f_spec cos / p (shadowing-masking, cosine, Fresnel) over the product lobe
//       (light x reflection SG): its clamped-cosine mean by [T24]'s D, the visibility ratio at
//       the mean cosine of its part above the horizon, Fresnel at the half vector of that part's
//       mean direction, pulled towards the tabulated albedo (ggxSpecularAlbedo) as the light
//       widens, so that a constant light returns the albedo.
// Exact for a constant light (up to the table, 1.4 %) and for lambda -> infinity; in between,
// errors against quadrature (SgMathGlossy.MatchesQuadrature) up to 23 % for the mirror-direction
// light and 38 % off it at n . v >= 0.3, up to 2.3x at grazing view (n . v = 0.05) for
// lambda ~ 10..100: docs/techniques/sg-lighting.md. >= 0 and finite for sharpness in [0, 2^41]
// and beyond, alpha in [0, 1], any view (n . v < 0 included) and light axis.
glm::dvec3 sgGgxReflection(const Sg& light, glm::dvec3 normal, glm::dvec3 view, double alpha,
                           glm::dvec3 f0, double f90);

// The same split in two, for a receiver summing many lights: sgGgxReceiver holds every term that
// depends only on the receiver (the view frame, the dominant reflection direction, the
// reflection SG and the wide-light end of E, which needs the albedo table and a clamped-cosine
// integral), computed once; sgGgxReflection(light, receiver) adds one light. The shading pass
// does the same per pixel (shaders/common/sg_lighting.glsl).
struct SgGgxReceiver {
  glm::dvec3 normal{0.0, 0.0, 1.0};
  glm::dvec3 ex{1.0, 0.0, 0.0}, ey{0.0, 1.0, 0.0};  // view frame: ex along the view's tangent
  glm::dvec3 wo{0.0, 0.0, 1.0};                     // the view in that frame, n . v clamped
  double nv = 1.0;                                  // clamped n . v
  double alpha2 = 1.0;                              // floored alpha, squared
  double q = 0.0;                                   // (1 - alpha^2) / alpha^2
  double reflectionSharpness = 0.0;                 // q / 2
  glm::dvec3 dominantReflection{0.0, 0.0, 1.0};     // in the view frame
  glm::dvec3 f0{0.0};
  double f90 = 1.0;
  glm::dvec3 logWideFactor{0.0};  // log(A(f0, f90) / W_0), E's constant-light end
};
SgGgxReceiver sgGgxReceiver(glm::dvec3 normal, glm::dvec3 view, double alpha, glm::dvec3 f0,
                            double f90);
glm::dvec3 sgGgxReflection(const Sg& light, const SgGgxReceiver& receiver);

}  // namespace gi
