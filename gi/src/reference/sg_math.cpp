#include "reference/sg_math.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;
// Positional-variance floor relative to the squared distance, v >= d^2 / 2^41 ([R], section
// 4.1): keeps lambda_x = d^2 / v <= 2^41 for zero-variance (single-texel) VSGLs, the same cap as
// VSGL_MAX_SHARPNESS.
constexpr double kVarianceFloorScale = 0x1p-41;
// Absolute variance floor (FLT_MIN): with d = 0 and v = 0 (a zero-variance VSGL exactly at the
// receiver, section 12 case 12) the radiance is a genuine point singularity; the floor makes it
// huge but finite instead of 0 / 0, and FLT_MIN is the floor the fp32 shader can use as well.
constexpr double kMinVariance = 0x1p-126;
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
  const glm::dvec3 mean(lobe.meanVariance);
  const double variance = lobe.meanVariance.w;
  // The fp32 axis is unit only to ~1e-7, which sharpnesses up to 2^41 would amplify in the
  // product (whose log amplitude assumes unit axes); a zero axis comes with sharpness 0.
  const glm::dvec3 axis = safeNormalize(glm::dvec3(lobe.axisSharpness), {0.0, 0.0, 1.0});
  const double sharpness = lobe.axisSharpness.w;

  const glm::dvec3 toLight = mean - receiver;
  const double distance2 = glm::dot(toLight, toLight);
  const double distance = std::sqrt(distance2);
  const double clampedVariance =
      std::max({variance, distance2 * kVarianceFloorScale, kMinVariance});

  // Emitted SG over incident directions (they point back along -xi), times the planar
  // Gaussian spot seen from the receiver, G(w; l / d, d^2 / v) (section 4.1). At d = 0 the spot
  // sharpness is 0 and its axis irrelevant (section 12 case 12).
  const Sg emitted{-axis, sharpness, 0.0};
  const Sg spot{distance > 0.0 ? toLight / distance : -axis, distance2 / clampedVariance, 0.0};

  VsglIncomingRadiance radiance;
  radiance.sg = sgProduct(emitted, spot);
  // E = Phi / (2 pi v S(lambda)) (section 3.4): 2-D Gaussian times vMF normalisation.
  radiance.scale = glm::dvec3(lobe.power) / (2.0 * kPi * clampedVariance * sgIntegral(sharpness));
  return radiance;
}

glm::dvec3 vsglDiffuseRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver, glm::dvec3 normal,
                               glm::dvec3 albedo) {
  const VsglIncomingRadiance radiance = vsglIncomingRadiance(lobe, receiver);
  const double d =
      sgClampedCosineIntegralOverPi(radiance.sg.sharpness, glm::dot(radiance.sg.axis, normal));
  return albedo * radiance.scale * (std::exp(radiance.sg.logAmplitude) * d);
}

}  // namespace gi
