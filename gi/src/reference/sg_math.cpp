#include "reference/sg_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;
// Below these the interpolation factors are replaced by their lambda -> 0 limit, (1 + c) / 2:
// the ratios they guard are 0 / 0 at 0, and the limit is exact to O(tau^2) = 1e-200.
constexpr double kTinySteepness = 1e-100;
// The Taylor branch of U and L (section 4.3): below 0.5 the closed forms lose digits to
// cancellation (about eps * 0.5 / U at the switch, 5e-16, so the branches meet continuously).
constexpr double kTaylorSwitch = 0.5;
// Terms of the Taylor series: the k-th term is at most 0.5^k / (k + 2)!, below 1e-19 of the
// leading 1/2 from k = 15 on, so 16 terms are exact in double.
constexpr int kTaylorTerms = 16;

glm::dvec3 safeNormalize(glm::dvec3 v, glm::dvec3 fallback) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : fallback;
}

// sum_k coefficient(k) lambda^k for k < kTaylorTerms, by Horner from the smallest term.
template <typename Coefficient>
double taylor(double lambda, Coefficient coefficient) {
  double sum = 0.0;
  for (int k = kTaylorTerms - 1; k >= 0; --k) sum = sum * lambda + coefficient(k);
  return sum;
}

// 1 / n! in double.
double inverseFactorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) f *= double(i);
  return 1.0 / f;
}

}  // namespace

double em1x(double x) {
  // expm1 carries full relative accuracy to the smallest subnormals, so only x = 0 is special.
  return x == 0.0 ? 1.0 : std::expm1(x) / x;
}

double sgIntegral(double lambda) {
  return 4.0 * kPi * em1x(-2.0 * lambda);
}

double sgEvaluate(glm::dvec3 omega, glm::dvec3 axis, double lambda) {
  const glm::dvec3 d = omega - axis;
  return std::exp(-0.5 * lambda * glm::dot(d, d));
}

double sgEvaluate(const Sg& sg, glm::dvec3 omega) {
  const glm::dvec3 d = omega - sg.axis;
  return std::exp(sg.logAmplitude - 0.5 * sg.sharpness * glm::dot(d, d));
}

Sg sgProduct(const Sg& a, const Sg& b) {
  const glm::dvec3 u = a.sharpness * a.axis + b.sharpness * b.axis;
  // |u| through the largest component: the same as sqrt(u . u), but without underflow for
  // nearly cancelling lobes, so the axis stays unit down to subnormal |u|.
  const double largest = std::max({std::abs(u.x), std::abs(u.y), std::abs(u.z)});
  Sg p;
  if (largest > 0.0) {
    const glm::dvec3 scaled = u / largest;
    const double length = glm::length(scaled);
    p.sharpness = largest * length;
    p.axis = scaled / length;
  } else {
    // Opposite axes with equal sharpness, or both sharpnesses 0: the product is constant over
    // the sphere, and any unit axis is exact (section 12 case 8).
    p.sharpness = 0.0;
    p.axis = a.axis;
  }
  // l_p = lambda_p - l1 - l2, in the form of section 4.2 that does not cancel when both lobes
  // are sharp; the denominator is 0 only when every sharpness is 0, where l_p = 0.
  const glm::dvec3 gap = a.axis - b.axis;
  const double denominator = p.sharpness + a.sharpness + b.sharpness;
  const double logProduct =
      denominator > 0.0 ? -a.sharpness * b.sharpness * glm::dot(gap, gap) / denominator : 0.0;
  p.logAmplitude = a.logAmplitude + b.logAmplitude + logProduct;
  return p;
}

double sgInnerProduct(const Sg& a, const Sg& b) {
  const Sg p = sgProduct(a, b);
  return std::exp(p.logAmplitude) * sgIntegral(p.sharpness);
}

double sgUpperHemisphericalIntegral(double lambda) {
  return em1x(-lambda);
}

double sgLowerHemisphericalIntegral(double lambda) {
  return std::exp(-lambda) * em1x(-lambda);
}

double sgHemisphericalLerpFactor(double lambda, double cosine) {
  // [T22] fit constants, section 4.2.
  constexpr double kA = 0.6517328826907056;
  constexpr double kB = 1.3418280033141288;
  constexpr double kC = 7.2216687798956709;
  const double c = std::clamp(cosine, -1.0, 1.0);
  // tau = lambda sqrt((lambda/2 + A) / ((lambda + B) lambda + C)); above 1 the same ratio with
  // numerator and denominator divided by lambda^2, so that huge lambda cannot overflow.
  const double tau =
      lambda <= 1.0 ? lambda * std::sqrt((0.5 * lambda + kA) / ((lambda + kB) * lambda + kC))
                    : std::sqrt(lambda) * std::sqrt((0.5 + kA / lambda) /
                                                    (1.0 + kB / lambda + kC / (lambda * lambda)));
  if (tau < kTinySteepness) return 0.5 + 0.5 * c;
  return std::clamp(0.5 + 0.5 * std::erf(tau * c) / std::erf(tau), 0.0, 1.0);
}

double sgHemisphericalIntegral(double lambda, double cosine) {
  const double upper = sgUpperHemisphericalIntegral(lambda);
  const double lower = sgLowerHemisphericalIntegral(lambda);
  return lower + sgHemisphericalLerpFactor(lambda, cosine) * (upper - lower);
}

double vmfUpperHemisphereFraction(double lambda, double cosine) {
  // The em1x(-lambda) common to H_up and H_low cancels against the vMF normalisation.
  const double e = std::exp(-lambda);
  return (e + sgHemisphericalLerpFactor(lambda, cosine) * (1.0 - e)) / (1.0 + e);
}

double clampedCosineUpperIntegral(double lambda) {
  // U = integral_0^1 mu e^(lambda (mu - 1)) d mu = (lambda - 1 + e^-lambda) / lambda^2
  //   = sum_k (-lambda)^k / (k + 2)!  (expanding e^-lambda).
  if (lambda <= kTaylorSwitch) {
    return taylor(lambda,
                  [](int k) { return (k % 2 == 0 ? 1.0 : -1.0) * inverseFactorial(k + 2); });
  }
  return (1.0 - em1x(-lambda)) / lambda;
}

double clampedCosineLowerIntegral(double lambda) {
  // L = integral_0^1 mu e^(-lambda (mu + 1)) d mu = e^-lambda (1 - e^-lambda (1 + lambda)) /
  // lambda^2 = e^-lambda sum_k (-lambda)^k (k + 1) / (k + 2)!  (expanding e^-lambda (1 + lambda)).
  if (lambda <= kTaylorSwitch) {
    return std::exp(-lambda) * taylor(lambda, [](int k) {
             return (k % 2 == 0 ? 1.0 : -1.0) * double(k + 1) * inverseFactorial(k + 2);
           });
  }
  const double e = std::exp(-lambda);
  return e * (em1x(-lambda) - e) / lambda;
}

double sgClampedCosineIntegralOverPi(double lambda, double cosine) {
  // [T24] fit constants for t(lambda), section 4.3 option 2.
  constexpr double kA = 2.7360831611272558;
  constexpr double kB = 17.021297781741875;
  constexpr double kC = 4.0100826728510421;
  constexpr double kD = 15.219156263147211;
  constexpr double kE = 76.087896272360737;
  const double c = std::clamp(cosine, -1.0, 1.0);
  // t = lambda sqrt(1/2 (lambda^2 + A lambda + B) / (lambda^3 + C lambda^2 + D lambda + E));
  // above 1 with numerator and denominator divided by lambda^3 (no overflow for huge lambda).
  double t = 0.0;
  if (lambda <= 1.0) {
    t = lambda * std::sqrt(0.5 * ((lambda + kA) * lambda + kB) /
                           (((lambda + kC) * lambda + kD) * lambda + kE));
  } else {
    const double r = 1.0 / lambda;
    t = std::sqrt(lambda) *
        std::sqrt(0.5 * ((kB * r + kA) * r + 1.0) / (((kE * r + kD) * r + kC) * r + 1.0));
  }
  double s = 0.5 + 0.5 * c;
  if (t >= kTinySteepness) {
    // erfc(-t c) and erfc(t) directly (not 1 - erf): no clamp at eps/2 is needed in double.
    s = 0.5 * (c * std::erfc(-t * c) + std::erfc(t)) -
        std::exp(-t * t * c * c) * std::expm1(t * t * (c * c - 1.0)) / (2.0 * std::sqrt(kPi) * t);
  }
  s = std::clamp(s, 0.0, 1.0);
  const double upper = clampedCosineUpperIntegral(lambda);
  const double lower = clampedCosineLowerIntegral(lambda);
  // U and L are per 2 pi; D is per pi, hence the 2 (D(0, c) = 2 * 1/2 = 1, the white furnace).
  return 2.0 * (lower + (upper - lower) * s);
}

VsglIncomingRadiance vsglIncomingRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver) {
  return vsglIncomingRadiance(lobe, receiver, VsglLobeEmission{}, glm::dvec3(0.0));
}

VsglIncomingRadiance vsglIncomingRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver,
                                          const VsglLobeEmission& emission, glm::dvec3 normal) {
  const glm::dvec3 mean(lobe.meanVariance);
  const double variance = lobe.meanVariance.w;
  // The fp32 axis is unit only to ~1e-7, which sharpnesses up to 2^41 would amplify in the
  // product (whose log amplitude assumes unit axes); a zero axis comes with sharpness 0.
  const glm::dvec3 axis = safeNormalize(glm::dvec3(lobe.axisSharpness), {0.0, 0.0, 1.0});
  const double sharpness = lobe.axisSharpness.w;

  const glm::dvec3 toLight = mean - receiver;
  const double distance2 = glm::dot(toLight, toLight);
  const double distance = std::sqrt(distance2);
  // Foreshortening f at the receiver's elevation above the cluster's plane, its cosine measured
  // against sqrt(d^2 + v): h / d far away, h / sqrt(v) inside the cluster, so that a receiver
  // in the plane gets f = 1 - beta however close it is to the mean.
  const double reach = std::sqrt(distance2 + variance);
  const double foreshortening =
      emission.flatness +
      (reach > 0.0 ? std::max(-glm::dot(emission.plane, toLight), 0.0) / reach : 0.0);
  const double spotVariance =
      std::max({foreshortening * variance, distance2 * kVarianceFloorScale, kMinVariance});
  // The planar Gaussian spot seen from the receiver, G(w; l / d, d^2 / v_f) (section 4.1). At
  // d = 0 its sharpness is 0 and its axis irrelevant (section 12 case 12).
  const Sg spot{distance > 0.0 ? toLight / distance : -axis, distance2 / spotVariance, 0.0};

  double emissionSharpness = sharpness;
  double normalisation =
      emission.normalisation < 0.0 ? sgIntegral(sharpness) : emission.normalisation;
  double keep = 1.0;
  if (emission.lambertian) {
    const double beta = 1.0 - emission.flatness;
    const double near = sharpness / std::max(sharpness + spot.sharpness, kMinVariance);
    emissionSharpness = emission.flatness * sharpness + beta * sharpness * near;
    normalisation = emission.flatness * sgIntegral(emissionSharpness) +
                    beta * 2.0 * kPi * clampedCosineUpperIntegral(emissionSharpness);
    keep = 1.0 - near * std::max(glm::dot(emission.plane, normal), 0.0);
  }
  // Emitted SG over incident directions (they point back along -xi), times the spot.
  const Sg emitted{-axis, emissionSharpness, 0.0};

  VsglIncomingRadiance radiance;
  radiance.sg = sgProduct(emitted, spot);
  // E = Phi f / (2 pi v_f N) (section 3.4 with N for S): 2-D Gaussian times the emission's
  // normalisation, so that the spot's integral 2 pi v_f / d^2 leaves I(-w_l) / d^2.
  radiance.scale =
      glm::dvec3(lobe.power) * (keep * foreshortening / (2.0 * kPi * spotVariance * normalisation));
  return radiance;
}

glm::dvec3 vsglDiffuseRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver, glm::dvec3 normal,
                               glm::dvec3 albedo) {
  const VsglIncomingRadiance radiance = vsglIncomingRadiance(lobe, receiver);
  const double d =
      sgClampedCosineIntegralOverPi(radiance.sg.sharpness, glm::dot(radiance.sg.axis, normal));
  return albedo * radiance.scale * (std::exp(radiance.sg.logAmplitude) * d);
}

// ---------------------------------------------------------------------------------------------
// Glossy (section 4.4).

namespace {

// Weight of the sharp-light terms, w = lambda / (lambda + lambda_r + kWideLightBias): the
// bias keeps w small for a wide light on a rough surface (lambda_r -> 0 as alpha -> 1), where
// the tabulated albedo, not the light's own direction, sets the mean of f cos / p (Fresnel
// included). Chosen by the measured error: with 0 instead of 2 the worst alpha = 1 error at
// n . v >= 0.3 grows from 20 % to 127 % (SgMathGlossy.MatchesQuadrature, lambda = 0.1, f0 = 0.04).
constexpr double kWideLightBias = 2.0;
// Length of the view's tangential part below which the view counts as normal incidence.
constexpr double kSgGgxMinTangential = 1e-4;
// FLT_MIN, the floor of the logarithms below (the GLSL port uses the same).
constexpr double kFltMin = 0x1p-126;
// Abramowitz and Stegun 5.1.53: E1(x) + ln x for 0 < x <= 1, |error| < 2e-7.
constexpr double kE1Series[6] = {-0.57721566, 0.99999193,  -0.24991055,
                                 0.05519968,  -0.00976004, 0.00107857};
// Abramowitz and Stegun 5.1.54: x e^x E1(x) = P(x) / Q(x) for x >= 1, |error| < 2e-8, with
// monic quartics P and Q (coefficients of x^3 .. x^0).
constexpr double kE1P[4] = {8.5733287401, 18.0590169730, 8.6347608925, 0.2677737343};
constexpr double kE1Q[4] = {9.5733223454, 25.6329561486, 21.0996530827, 3.9584969228};

// The GGX smith term of the reflection pdf, s(c) = sqrt(alpha^2 + (1 - alpha^2) c^2) (the
// projected area of the unit-height GGX ellipsoid seen at cosine c; 2 s / (c + s) is G1).
double ggxProjectedArea(double alpha2, double cosine) {
  return std::sqrt(alpha2 + (1.0 - alpha2) * cosine * cosine);
}

// Schlick's Fresnel with F90, as brdf.glsl.
glm::dvec3 schlickFresnel(glm::dvec3 f0, double f90, double cosine) {
  const double m = 1.0 - std::max(cosine, 0.0);
  const double m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

// The mean over an SG lobe (axis, sharpness; unnormalised) of f_spec cos / p without Fresnel,
//   W(c) = 2 c s_v / (c s_v + n_v s(c)),  c = w . n > 0, s_v = s(n_v)
// (brdf.glsl's D Vis c over the pdf D / (4 s_v)), as W(c) = c g(c): the clamped-cosine mean
// E[c^+] = pi D(lambda, axis_z) / S(lambda) ([T24], section 4.3) times g at the mean cosine of
// the part above the horizon, E[c^+] / P(c > 0) (P the vMF upper fraction, section 4.2), which
// is returned in `upperCosine`.
double ggxVisibilityRatioMean(double sharpness, double axisCosine, double nv, double alpha2,
                              double& upperCosine) {
  const double meanCosine =
      kPi * sgClampedCosineIntegralOverPi(sharpness, axisCosine) / sgIntegral(sharpness);
  const double upper = vmfUpperHemisphereFraction(sharpness, axisCosine);
  const double c = upper > 0.0 ? std::clamp(meanCosine / upper, 0.0, 1.0) : 0.0;
  upperCosine = c;
  const double sv = ggxProjectedArea(alpha2, nv);
  return meanCosine * 2.0 * sv / (c * sv + nv * ggxProjectedArea(alpha2, c));
}

}  // namespace

double sgGgxPeakCorrection(double beta) {
  if (!(beta > 0.0)) return 1.0;  // beta = 0: the lobe is only the light
  if (beta > 100.0) {
    // Asymptotic series: 1 - 1/beta + 4/beta^2 - 18/beta^3 + 96/beta^4 (truncation < 1e-7).
    const double y = 1.0 / beta;
    return 1.0 + y * (-1.0 + y * (4.0 + y * (-18.0 + y * 96.0)));
  }
  double kappa = 0.0;  // 1 - beta e^beta E1(beta)
  if (beta <= 1.0) {
    double poly = 0.0;
    for (int k = 5; k >= 0; --k) poly = poly * beta + kE1Series[k];
    kappa = 1.0 - beta * std::exp(beta) * (poly - std::log(beta));
  } else {
    // 1 - P/Q = (Q - P) / Q, differences of the coefficients: no cancellation as P/Q -> 1.
    double q = 1.0, d = 0.0;
    for (int k = 0; k < 4; ++k) {
      q = q * beta + kE1Q[k];
      d = d * beta + (kE1Q[k] - kE1P[k]);
    }
    kappa = d / q;
  }
  return kappa * (1.0 + beta);
}

glm::dvec2 ggxSpecularAlbedo(double nv, double alpha) {
  const double last = double(kGgxAlbedoTableSize - 1);
  const double u = std::sqrt(std::clamp(nv, kSgGgxMinViewCosine, 1.0)) * last;
  const double t = std::sqrt(std::clamp(alpha, kSgGgxMinAlpha, 1.0)) * last;
  const int i = std::min(int(u), kGgxAlbedoTableSize - 2),
            j = std::min(int(t), kGgxAlbedoTableSize - 2);
  const double fu = u - double(i), ft = t - double(j);
  return glm::mix(
      glm::mix(ggxSpecularAlbedoNode(i, j), ggxSpecularAlbedoNode(i, j + 1), ft),
      glm::mix(ggxSpecularAlbedoNode(i + 1, j), ggxSpecularAlbedoNode(i + 1, j + 1), ft), fu);
}

SgGgxReceiver sgGgxReceiver(glm::dvec3 normal, glm::dvec3 view, double alpha, glm::dvec3 f0,
                            double f90) {
  SgGgxReceiver r;
  r.normal = normal;
  r.f0 = f0;
  r.f90 = f90;
  const double a = std::clamp(alpha, kSgGgxMinAlpha, 1.0);
  r.alpha2 = a * a;

  // View frame (x along the view's tangential part, z = n): the filtered NDF below is diagonal
  // in it. n . v is clamped like brdf.glsl, and the view rebuilt at that cosine.
  r.nv = std::max(glm::dot(normal, view), kSgGgxMinViewCosine);
  const glm::dvec3 tangential = view - glm::dot(normal, view) * normal;
  const double tangentialLength = glm::length(tangential);
  if (tangentialLength > kSgGgxMinTangential) {
    r.ex = tangential / tangentialLength;
  } else {
    // Within 1e-4 rad of the normal (or of its opposite) the azimuth of the view is lost to
    // rounding (in fp32 first) and the lobe is isotropic to O(1e-8): any tangent will do.
    const glm::dvec3 helper =
        std::abs(normal.x) < 0.6 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    r.ex = glm::normalize(glm::cross(helper, normal));
  }
  r.ey = glm::cross(normal, r.ex);
  r.wo = glm::dvec3(std::sqrt(std::max(1.0 - r.nv * r.nv, 0.0)), 0.0, r.nv);

  // Dominant reflection direction: the mirror image of the view about the dominant visible
  // normal, the centre of the GGX spherical-cap VNDF (Dupuy and Benyoub 2023, as
  // GGXDominantVisibleNormal in [R]; n . v > 0 here, so the plain form is stable).
  const double t = std::sqrt(r.alpha2 * r.wo.x * r.wo.x + r.nv * r.nv);
  const glm::dvec3 dominantNormal = glm::normalize(glm::dvec3(r.alpha2 * r.wo.x, 0.0, t + r.nv));
  r.dominantReflection = 2.0 * glm::dot(r.wo, dominantNormal) * dominantNormal - r.wo;
  // Reflection SG sharpness (1 - alpha^2) / (2 alpha^2) ([R]'s "conservative" sharpness): the
  // NDF as an SG of sharpness 2 / alpha^2 - 2 ([TH19]) mapped to reflection directions with the
  // in-plane Jacobian 1/4. Its normalised peak equals the GGX reflection pdf's peak at normal
  // incidence for small alpha. q = 1 / (projected roughness) = (1 - alpha^2) / alpha^2.
  r.q = (1.0 - r.alpha2) / r.alpha2;
  r.reflectionSharpness = 0.5 * r.q;

  // The wide-light end of E (see sgGgxReflection): the tabulated albedo A(f0) over the model's
  // own value W_0 for a constant light (the reflection SG alone), as a logarithm with an FLT_MIN
  // floor: A can be 0 (f0 = 0 at normal incidence), where the factor is 0 either way; the floor
  // keeps 0^0 out of the w = 0 limit.
  double upperCosineWide = 0.0;
  const double ratioWide = ggxVisibilityRatioMean(r.reflectionSharpness, r.dominantReflection.z,
                                                  r.nv, r.alpha2, upperCosineWide);
  const glm::dvec2 table = ggxSpecularAlbedo(r.nv, a);
  // A = F90 x + F0 (y - x): Schlick's F0 + (F90 - F0) s integrated against the table's two
  // moments (x: of s alone, y: of 1).
  const glm::dvec3 albedo = f90 * table.x + f0 * (table.y - table.x);
  for (int c = 0; c < 3; ++c) {
    r.logWideFactor[c] = std::log(std::max(albedo[c], kFltMin) / std::max(ratioWide, kFltMin));
  }
  return r;
}

glm::dvec3 sgGgxReflection(const Sg& light, const SgGgxReceiver& r) {
  const double lambda = std::max(light.sharpness, 0.0);
  const double nv = r.nv, q = r.q;
  const glm::dvec3 wo = r.wo;
  const glm::dvec3 xi(glm::dot(light.axis, r.ex), glm::dot(light.axis, r.ey),
                      glm::dot(light.axis, r.normal));

  // K, sharp-light part: [T24] Section 5.2 NDF filtering. In projected space the GGX has the
  // variance-like matrix p I (p = alpha^2 / (1 - alpha^2), [TK21] Eq. 4), the light adds
  // 2 sigma^2 J J^T with sigma^2 = 1 / lambda and J = R diag(1/2, 1/(2 n_v)) the half-vector ->
  // reflection Jacobian at h = n; in the view frame everything is diagonal, so [T24]'s return
  // to slope space, (S + det S I) / (1 + tr S + det S), is exactly S_ii / (1 + S_ii). Written
  // with lambda q S_ii = b_i (finite for lambda = 0 and alpha = 1, no overflow up to 2^41):
  //   b = (lambda + q/2, lambda + q / (2 n_v^2)),  m_i = b_i / (lambda q + b_i).
  const double lq = lambda * q;
  const double b1 = lambda + 0.5 * q, b2 = lambda + 0.5 * q / (nv * nv);
  const double m1 = lq + b1 > 0.0 ? b1 / (lq + b1) : 1.0;
  const double m2 = lq + b2 > 0.0 ? b2 / (lq + b2) : 1.0;
  // Reflection pdf of the symmetric GGX with roughness matrix diag(m1, m2) at the half vector
  // of the view and the light axis ([R] SGGXReflectionPDF): D(h) / (4 sqrt(m1 wo_x^2 + nv^2)).
  const glm::dvec3 halfSum = wo + xi;
  const double halfLength = glm::length(halfSum);
  const glm::dvec3 h = halfLength > 0.0 ? halfSum / halfLength : glm::dvec3(0.0, 0.0, 1.0);
  const double stretched = h.x * h.x / m1 + h.y * h.y / m2 + h.z * h.z;
  const double ndf = 1.0 / (kPi * std::sqrt(m1 * m2) * stretched * stretched);
  const double filteredPdf = ndf / (4.0 * std::sqrt(m1 * wo.x * wo.x + nv * nv));
  const double sharpMass = sgIntegral(lambda) * filteredPdf;

  // K, wide-light part: the light times the normalised reflection SG, an exact SG inner product
  // (section 4.2) divided by S(lambda_r).
  const Sg unitLight{xi, lambda, 0.0};
  const Sg reflection{r.dominantReflection, r.reflectionSharpness, 0.0};
  const Sg product = sgProduct(unitLight, reflection);
  const double wideMass = std::exp(product.logAmplitude) * sgIntegral(product.sharpness) /
                          sgIntegral(r.reflectionSharpness);

  // Both parts predict 1 / (1 + beta) for the peak of a small-angle GGX lobe convolved with the
  // light, beta = lambda / (2 lambda_r) = lambda alpha^2 / (1 - alpha^2); the exact t x Gaussian
  // peak is (1 - beta e^beta E1(beta)), hence the correction (up to -19 %).
  const double w = lambda / (lambda + r.reflectionSharpness + kWideLightBias);
  const double beta = q > 0.0 ? lambda / q : std::numeric_limits<double>::infinity();
  const double mass = sgGgxPeakCorrection(beta) * (w * sharpMass + (1.0 - w) * wideMass);

  // E: the mean W_q of f cos / p over the product lobe without Fresnel, Fresnel F_q at the half
  // vector of the lobe's lit part (below), and the same model's W_0 for a constant light (the
  // reflection SG alone), whose ratio to the tabulated albedo A(f0) corrects the model as the
  // light widens (r.logWideFactor):
  //   E = W_q F_q^w (A(f0) / W_0)^(1 - w),
  // exact for a constant light (w = 0: E = A) and, for a sharp light (w -> 1), the visibility
  // ratio and Fresnel at the light direction. (A geometric rather than linear blend: measured
  // better for f0 = 0.04, where F_q and A / W_0 differ by up to 10x.)
  double upperCosine = 0.0;
  const double ratio =
      ggxVisibilityRatioMean(product.sharpness, product.axis.z, nv, r.alpha2, upperCosine);
  // Fresnel direction: the product axis raised (or lowered) to the mean cosine of its part above
  // the horizon, at the axis' azimuth. F varies fastest at grazing half vectors, i.e. for the
  // lobes the horizon cuts; the unlit part below must not set it. A sharp light above the
  // horizon keeps its own direction (upperCosine -> axis_z).
  const double horizontal = std::hypot(product.axis.x, product.axis.y);
  const double sine = std::sqrt(std::max(1.0 - upperCosine * upperCosine, 0.0));
  const glm::dvec3 fresnelAxis = horizontal > 0.0
                                     ? glm::dvec3(product.axis.x / horizontal * sine,
                                                  product.axis.y / horizontal * sine, upperCosine)
                                     : glm::dvec3(0.0, 0.0, 1.0);
  const glm::dvec3 lobeHalf = wo + fresnelAxis;
  const double lobeHalfLength = glm::length(lobeHalf);
  const double vh = lobeHalfLength > 0.0 ? glm::dot(wo, lobeHalf) / lobeHalfLength : 0.0;
  const glm::dvec3 fresnel = schlickFresnel(r.f0, r.f90, vh);
  glm::dvec3 result(0.0);
  for (int c = 0; c < 3; ++c) {
    // The FLT_MIN floor as in logWideFactor: F is 0 where f0 = 0 at normal incidence.
    const double logE =
        w * std::log(std::max(fresnel[c], kFltMin)) + (1.0 - w) * r.logWideFactor[c];
    result[c] = mass * ratio * std::exp(logE);
  }
  return result;
}

glm::dvec3 sgGgxReflection(const Sg& light, glm::dvec3 normal, glm::dvec3 view, double alpha,
                           glm::dvec3 f0, double f90) {
  return sgGgxReflection(light, sgGgxReceiver(normal, view, alpha, f0, f90));
}

}  // namespace gi
