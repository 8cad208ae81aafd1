// The SG math oracle (gi/src/reference/sg_math.h) tested as math: limits and continuity of the
// stable forms, the product and inner product, the [T22] hemispherical and [T24] clamped-cosine
// fits against quadrature, and the VSGL radiance cases of vsgl-math.md section 12 (8, 9, 12, 13,
// 18). Quadrature is a fixed grid, so every number below is deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "reference/sg_math.h"

namespace gi {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// Sharpness clamp of the VSGL record (section 12 case 7).
constexpr double kMaxSharpness = VSGL_MAX_SHARPNESS;
// The diffuse lobe's vMF sharpness (section 3.3), a typical VSGL sharpness.
constexpr double kDiffuseSharpness = 2.292504;

double relativeError(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// An orthonormal frame whose third axis is `pole`.
struct Frame {
  glm::dvec3 tangent, bitangent, pole;
};

Frame frameAround(glm::dvec3 pole) {
  const glm::dvec3 helper =
      std::abs(pole.x) < 0.6 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 tangent = glm::normalize(glm::cross(helper, pole));
  return {tangent, glm::cross(pole, tangent), pole};
}

// Fixed quadrature over the cap theta < thetaMax about frame.pole: composite 8-point
// Gauss-Legendre in theta (uniform panels) times the periodic midpoint rule in phi. The phi rule
// converges geometrically for the smooth periodic integrands here (for a Gaussian of angular
// width sigma and step h the error is ~exp(-2 pi^2 sigma^2 / h^2)), and 8-point Gauss on panels
// narrower than the lobe is exact to degree 15, so the grid is far more accurate than the fits
// it checks: SgMathQuadrature measures it against closed forms (< 1e-12 relative).
class SphereQuadrature {
 public:
  SphereQuadrature(int panels, int phiSteps) : panels_(panels) {
    // Gauss-Legendre nodes by Newton's method on P_8 (Chebyshev-like starting guesses).
    constexpr int n = kGaussNodes;
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (double(i) + 0.75) / (double(n) + 0.5));
      double derivative = 0.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / double(k);
          p0 = p1;
          p1 = p2;
        }
        derivative = double(n) * (z * p1 - p0) / (z * z - 1.0);
        const double step = p1 / derivative;
        z -= step;
        if (std::abs(step) < 1e-16) break;
      }
      nodes_[i] = z;
      weights_[i] = 2.0 / ((1.0 - z * z) * derivative * derivative);
    }
    for (int j = 0; j < phiSteps; ++j) {
      const double phi = 2.0 * kPi * (double(j) + 0.5) / double(phiSteps);
      cosPhi_.push_back(std::cos(phi));
      sinPhi_.push_back(std::sin(phi));
    }
  }

  template <typename F>
  double integrate(const Frame& frame, double thetaMax, F f) const {
    const double panel = thetaMax / double(panels_);
    const double phiWeight = 2.0 * kPi / double(cosPhi_.size());
    double total = 0.0;
    for (int p = 0; p < panels_; ++p) {
      for (int i = 0; i < kGaussNodes; ++i) {
        const double theta = panel * (double(p) + 0.5 + 0.5 * nodes_[i]);
        const double sinTheta = std::sin(theta), cosTheta = std::cos(theta);
        double ring = 0.0;
        for (size_t j = 0; j < cosPhi_.size(); ++j) {
          const glm::dvec3 omega =
              sinTheta * (cosPhi_[j] * frame.tangent + sinPhi_[j] * frame.bitangent) +
              cosTheta * frame.pole;
          ring += f(omega);
        }
        total += 0.5 * panel * weights_[i] * sinTheta * phiWeight * ring;
      }
    }
    return total;
  }

 private:
  static constexpr int kGaussNodes = 8;
  int panels_;
  std::array<double, kGaussNodes> nodes_{};
  std::array<double, kGaussNodes> weights_{};
  std::vector<double> cosPhi_, sinPhi_;
};

// Two fixed grids, picked by the sharpness of the integrand: panels of 5.6 degrees and 64 phi
// steps up to sharpness kCoarseLimit (angular width >= 0.22 rad, several nodes per width), and
// panels of 1.4 degrees with 256 phi steps above (down to width 0.032 rad at sharpness 1000).
// SgMathQuadrature.ExactForClosedForms measures both.
constexpr double kCoarseLimit = 20.0;
template <typename F>
double integrateCap(double sharpness, const Frame& frame, double thetaMax, F f) {
  // Panels per quarter turn of theta, so that the hemisphere and the sphere share a width.
  static const SphereQuadrature coarse(16, 64), fine(64, 256);
  static const SphereQuadrature coarseFull(32, 64), fineFull(128, 256);
  const bool full = thetaMax > 0.5 * kPi;
  const SphereQuadrature& q =
      sharpness <= kCoarseLimit ? (full ? coarseFull : coarse) : (full ? fineFull : fine);
  return q.integrate(frame, thetaMax, f);
}
template <typename F>
double integrateSphere(double sharpness, const Frame& frame, F f) {
  return integrateCap(sharpness, frame, kPi, f);
}
template <typename F>
double integrateUpperHemisphere(double sharpness, F f) {
  return integrateCap(sharpness, frameAround({0.0, 0.0, 1.0}), 0.5 * kPi, f);
}

// The SG axis with axis . n = c for n = +z.
glm::dvec3 axisAtCosine(double c) {
  return {std::sqrt(std::max(0.0, 1.0 - c * c)), 0.0, c};
}

// (1/2 pi) integral of G(w; xi, lambda) over w . n > 0, by quadrature (n = +z).
double hemisphericalQuadrature(double lambda, double c) {
  const glm::dvec3 axis = axisAtCosine(c);
  return integrateUpperHemisphere(lambda,
                                  [&](glm::dvec3 w) { return sgEvaluate(w, axis, lambda); }) /
         (2.0 * kPi);
}

// (1/pi) integral of G(w; xi, lambda) (w . n)^+, by quadrature (n = +z).
double clampedCosineQuadrature(double lambda, double c) {
  const glm::dvec3 axis = axisAtCosine(c);
  return integrateUpperHemisphere(lambda,
                                  [&](glm::dvec3 w) { return sgEvaluate(w, axis, lambda) * w.z; }) /
         kPi;
}

gpu::VsglLobe makeLobe(glm::dvec3 mean, double variance, glm::dvec3 axis, double sharpness,
                       glm::dvec3 power) {
  gpu::VsglLobe lobe{};
  lobe.meanVariance = glm::vec4(glm::dvec4(mean, variance));
  lobe.axisSharpness = glm::vec4(glm::dvec4(glm::normalize(axis), sharpness));
  lobe.power = glm::vec4(glm::dvec4(power, 1.0));
  return lobe;
}

bool isFinite(glm::dvec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// ---------------------------------------------------------------------------------------------
// Scalars: em1x, S, evaluation (section 4.2; section 12 case 9).

TEST(SgMathScalar, Em1xMatchesHighPrecisionAndIsContinuous) {
  // em1x at 0 and on subnormals is exactly 1; elsewhere within a few ulps of 40-digit values
  // (mpmath).
  EXPECT_EQ(em1x(0.0), 1.0);
  EXPECT_EQ(em1x(std::numeric_limits<double>::denorm_min()), 1.0);
  EXPECT_EQ(em1x(-std::numeric_limits<double>::denorm_min()), 1.0);
  struct Case {
    double x, value;
  };
  const Case cases[] = {{1e-8, 1.0000000050000000167},      {-1e-8, 0.99999999500000001667},
                        {0.5, 1.2974425414002562937},       {-0.5, 0.78693868057473315279},
                        {1.0, 1.7182818284590452354},       {-1.0, 0.6321205588285576784},
                        {-2.0, 0.43233235838169365405},     {-30.0, 0.033333333333330214126},
                        {700.0, 1.4489029353357207278e+301}};
  for (const Case& c : cases) EXPECT_LE(relativeError(em1x(c.x), c.value), 4.0 * kEps) << c.x;
  // The fp32 shader switches formulas at |x| = 1 and x = 0; the oracle has to be continuous
  // there to 1e-12 (it has no switch; the jump is rounding only).
  for (double x : {1.0, -1.0, 1e-300, -1e-300}) {
    const double below = em1x(std::nextafter(x, -2.0)), above = em1x(std::nextafter(x, 2.0));
    EXPECT_LE(relativeError(below, above), 1e-12) << x;
  }
}

TEST(SgMathScalar, IntegralLimits) {
  // Section 12 case 9: S(1e-8) = 4 pi (1 - 1e-8 + O(1e-16)), S(2^41) = 2 pi / 2^41 (not 0).
  EXPECT_LE(relativeError(sgIntegral(1e-8), 4.0 * kPi), 1.01e-8);
  EXPECT_LE(relativeError(sgIntegral(1e-8), 4.0 * kPi * (1.0 - 1e-8)), 4.0 * kEps);
  EXPECT_EQ(sgIntegral(0.0), 4.0 * kPi);
  EXPECT_LE(relativeError(sgIntegral(kMaxSharpness), 2.0 * kPi / kMaxSharpness), kEps);
  EXPECT_LE(relativeError(sgIntegral(1e300), 2.0 * kPi / 1e300), kEps);
  // Exact closed form 2 pi (1 - e^(-2 lambda)) / lambda where it does not cancel.
  for (double lambda : {0.5, 1.0, 10.0, 1000.0})
    EXPECT_LE(relativeError(sgIntegral(lambda), 2.0 * kPi * -std::expm1(-2.0 * lambda) / lambda),
              4.0 * kEps)
        << lambda;
  // No jump where the shader's em1x switches (2 lambda = 1).
  EXPECT_LE(
      relativeError(sgIntegral(std::nextafter(0.5, 0.0)), sgIntegral(std::nextafter(0.5, 1.0))),
      1e-12);
}

TEST(SgMathScalar, EvaluateIsAccurateNearThePeak) {
  // theta = 1e-9 rad off a lobe of sharpness 1e12: exp(lambda (cos - 1)) rounds cos to 1 and
  // returns 1; the exact value is exp(-2 lambda sin^2(theta / 2)) = exp(-5e-7).
  const double theta = 1e-9, lambda = 1e12;
  const glm::dvec3 omega(std::sin(theta), 0.0, std::cos(theta));
  const double exact = std::exp(-2.0 * lambda * std::pow(std::sin(0.5 * theta), 2));
  EXPECT_LE(relativeError(sgEvaluate(omega, {0.0, 0.0, 1.0}, lambda), exact), 1e-12);
  EXPECT_EQ(sgEvaluate({0.0, 0.0, 1.0}, {0.0, 0.0, 1.0}, kMaxSharpness), 1.0);
  // Antipode: exp(-2 lambda).
  EXPECT_LE(relativeError(sgEvaluate({0.0, 0.0, -1.0}, {0.0, 0.0, 1.0}, 3.0), std::exp(-6.0)),
            4.0 * kEps);
}

// ---------------------------------------------------------------------------------------------
// Product and inner product (section 4.2; section 12 case 8).

TEST(SgMathProduct, IdenticalAndOppositeAxes) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(1.0, -2.0, 3.0));
  const double sharpnesses[] = {0.0, 1e-6, 0.3, 7.0, 1e4, kMaxSharpness};
  for (double l1 : sharpnesses)
    for (double l2 : sharpnesses) {
      // Identical axes: l_p = 0 exactly, lambda_p = l1 + l2.
      const Sg same = sgProduct({axis, l1, 0.0}, {axis, l2, 0.0});
      EXPECT_EQ(same.logAmplitude, 0.0);
      EXPECT_LE(std::abs(same.sharpness - (l1 + l2)), 4.0 * kEps * (l1 + l2));
      // Opposite axes: l_p = -2 min(l1, l2), lambda_p = |l1 - l2|, a finite unit axis.
      const Sg opposite = sgProduct({axis, l1, 0.0}, {-axis, l2, 0.0});
      EXPECT_LE(std::abs(opposite.logAmplitude + 2.0 * std::min(l1, l2)),
                4.0 * kEps * std::min(l1, l2))
          << l1 << " " << l2;
      EXPECT_LE(std::abs(opposite.sharpness - std::abs(l1 - l2)), 4.0 * kEps * (l1 + l2));
      EXPECT_NEAR(glm::length(opposite.axis), 1.0, 4.0 * kEps);
      if (l1 == l2) {
        EXPECT_EQ(opposite.sharpness, 0.0);
      }
      EXPECT_TRUE(std::isfinite(sgInnerProduct({axis, l1, 0.0}, {-axis, l2, 0.0})));
    }
  // Input amplitudes multiply.
  const Sg scaled = sgProduct({axis, 2.0, 0.25}, {axis, 3.0, -1.0});
  EXPECT_DOUBLE_EQ(scaled.logAmplitude, -0.75);
}

TEST(SgMathProduct, StableLogAmplitudeAgreesWithNaiveWhereThatIsExact) {
  // For moderate sharpnesses lambda_p - l1 - l2 is accurate, and both forms must agree. For
  // sharp, nearly aligned lobes (below) the naive form is lost to cancellation (|l_p| = 2.5e-4
  // from terms of 2e9); the stable one keeps full precision.
  const glm::dvec3 a = glm::normalize(glm::dvec3(0.3, 0.1, 1.0));
  const glm::dvec3 b = glm::normalize(glm::dvec3(-0.5, 0.7, 0.4));
  for (double l1 : {0.1, 1.0, 5.0})
    for (double l2 : {0.2, 2.0, 9.0}) {
      const Sg p = sgProduct({a, l1, 0.0}, {b, l2, 0.0});
      EXPECT_LE(std::abs(p.logAmplitude - (p.sharpness - l1 - l2)), 1e-13 * (l1 + l2));
      // The product evaluated anywhere equals G1 G2.
      for (glm::dvec3 w : {a, b, glm::normalize(glm::dvec3(1.0, 1.0, -1.0))})
        EXPECT_LE(relativeError(sgEvaluate(p, w), sgEvaluate(w, a, l1) * sgEvaluate(w, b, l2)),
                  1e-13);
    }
  // Sharp, nearly aligned: l_p = -l1 l2 |a - b|^2 / (lp + l1 + l2); with l1 = l2 = l and a small
  // angle theta, -l theta^2 / 2 to O(theta^4).
  const double theta = 1e-6, l = 1e9;
  const Sg p =
      sgProduct({{0.0, 0.0, 1.0}, l, 0.0}, {{std::sin(theta), 0.0, std::cos(theta)}, l, 0.0});
  EXPECT_LE(relativeError(p.logAmplitude, -0.25 * l * theta * theta), 1e-9);
}

TEST(SgMathQuadrature, ExactForClosedForms) {
  // The accuracy of the fixed grids that the fit tests rely on, against exact integrals:
  // S(lambda) with the axis off the pole (exercises phi), U and L (axis at +-n, clamped cosine),
  // H_up and H_low, and the axis on the horizon (half of S by symmetry: a lobe cut in half by
  // the edge of the grid, sharp in phi). Both grids, either side of kCoarseLimit.
  double worst = 0.0;
  const Frame tilted = frameAround(glm::normalize(glm::dvec3(0.3, -0.4, 0.5)));
  for (double lambda : {0.1, 1.0, 10.0, kCoarseLimit, 21.0, 100.0, 1000.0}) {
    const glm::dvec3 axis = glm::normalize(glm::dvec3(0.9, 0.2, -0.3));
    const double full =
        integrateSphere(lambda, tilted, [&](glm::dvec3 w) { return sgEvaluate(w, axis, lambda); });
    worst = std::max(worst, relativeError(full, sgIntegral(lambda)));
    worst = std::max(worst, relativeError(clampedCosineQuadrature(lambda, 1.0),
                                          2.0 * clampedCosineUpperIntegral(lambda)));
    worst = std::max(worst, relativeError(hemisphericalQuadrature(lambda, 1.0),
                                          sgUpperHemisphericalIntegral(lambda)));
    worst = std::max(worst, relativeError(hemisphericalQuadrature(lambda, 0.0),
                                          sgIntegral(lambda) / (4.0 * kPi)));
    if (lambda <= 100.0) {  // below e^-200 the quadrature of the tail is meaningless
      worst = std::max(worst, relativeError(clampedCosineQuadrature(lambda, -1.0),
                                            2.0 * clampedCosineLowerIntegral(lambda)));
      worst = std::max(worst, relativeError(hemisphericalQuadrature(lambda, -1.0),
                                            sgLowerHemisphericalIntegral(lambda)));
    }
  }
  std::printf("quadrature vs closed forms: worst relative error %.2e\n", worst);
  EXPECT_LE(worst, 1e-12);
}

TEST(SgMathProduct, InnerProductMatchesQuadrature) {
  // G1 G2 integrated on a grid about the product axis, for every pair of sharpnesses, the axes
  // 70 degrees apart and (second loop) 170 degrees apart.
  const double lambdas[] = {0.1, 1.0, 10.0, 100.0};
  double worst = 0.0;
  for (double angle : {70.0, 170.0}) {
    const double a = angle * kPi / 180.0;
    const glm::dvec3 xi1 = glm::normalize(glm::dvec3(0.2, 0.3, 1.0));
    const Frame f = frameAround(xi1);
    const glm::dvec3 xi2 = std::cos(a) * xi1 + std::sin(a) * f.tangent;
    for (double l1 : lambdas)
      for (double l2 : lambdas) {
        const Sg g1{xi1, l1, 0.0}, g2{xi2, l2, 0.0};
        const Sg p = sgProduct(g1, g2);
        const double numeric = integrateSphere(p.sharpness, frameAround(p.axis), [&](glm::dvec3 w) {
          return sgEvaluate(w, xi1, l1) * sgEvaluate(w, xi2, l2);
        });
        const double error = relativeError(sgInnerProduct(g1, g2), numeric);
        EXPECT_LE(error, 1e-10) << angle << " " << l1 << " " << l2;
        worst = std::max(worst, error);
      }
  }
  std::printf("inner product vs quadrature: worst relative error %.2e\n", worst);
}

// ---------------------------------------------------------------------------------------------
// Hemispherical integrals (section 4.2, [T22]).

TEST(SgMathHemisphere, FitWithinBoundOfUpperIntegral) {
  // |fit - quadrature| against H_up for lambda in [0.1, 50], all c. Section 4.2 claims 0.4 %;
  // the fit's true worst case is 0.49 % (lambda = 7.7, c = 0.66; a 1.05-ratio lambda grid times
  // a 0.02 c grid), included below, so the bound is 0.5 %.
  double worst = 0.0, worstVmf = 0.0;
  for (double lambda : {0.1, 0.3, 1.0, 2.0, 3.5, 5.0, 7.7, 10.0, 20.0, 50.0})
    for (double c : {-1.0, -0.8, -0.5, -0.35, -0.1, 0.0, 0.3, 0.45, 0.66, 0.75, 0.9, 1.0}) {
      const double numeric = hemisphericalQuadrature(lambda, c);
      const double upper = sgUpperHemisphericalIntegral(lambda);
      const double error = std::abs(sgHemisphericalIntegral(lambda, c) - numeric) / upper;
      EXPECT_LE(error, 0.005) << lambda << " " << c;
      worst = std::max(worst, error);
      // The vMF fraction is the same fit divided by H_up + H_low, so its absolute error is at
      // most the same fraction.
      const double fraction = numeric / (upper + sgLowerHemisphericalIntegral(lambda));
      const double vmfError = std::abs(vmfUpperHemisphereFraction(lambda, c) - fraction);
      EXPECT_LE(vmfError, 0.005);
      worstVmf = std::max(worstVmf, vmfError);
    }
  std::printf("hemispherical fit: worst error %.2e of H_up; vMF fraction worst abs error %.2e\n",
              worst, worstVmf);
}

TEST(SgMathHemisphere, ExactAtPolesAndLimits) {
  for (double lambda : {0.0, 1e-8, 0.5, 3.0, 100.0, kMaxSharpness}) {
    EXPECT_EQ(sgHemisphericalLerpFactor(lambda, 1.0), 1.0);
    EXPECT_EQ(sgHemisphericalLerpFactor(lambda, -1.0), 0.0);
    const double e = std::exp(-lambda);
    EXPECT_DOUBLE_EQ(vmfUpperHemisphereFraction(lambda, 1.0), 1.0 / (1.0 + e));
    EXPECT_DOUBLE_EQ(vmfUpperHemisphereFraction(lambda, -1.0), e / (1.0 + e));
    for (double c : {-1.0, -0.3, 0.0, 1e-300, 0.7, 1.0}) {
      const double h = sgHemisphericalIntegral(lambda, c);
      EXPECT_TRUE(std::isfinite(h) && h >= 0.0) << lambda << " " << c;
    }
  }
  // lambda -> 0: the isotropic lobe puts 1 per 2 pi on each hemisphere, half of a vMF.
  EXPECT_EQ(sgHemisphericalIntegral(0.0, 0.3), 1.0);
  EXPECT_DOUBLE_EQ(vmfUpperHemisphereFraction(0.0, 0.3), 0.5);
}

// ---------------------------------------------------------------------------------------------
// SG x clamped cosine (section 4.3 option 2, [T24]).

TEST(SgMathDiffuse, UpperLowerAreExactAndContinuousAtTheTaylorSwitch) {
  // 40-digit values of U = (lambda - 1 + e^-l) / l^2 and L = e^-l (1 - e^-l (1 + l)) / l^2.
  struct Case {
    double lambda, upper, lower;
  };
  const Case cases[] = {{1e-6, 0.49999983333337499999, 0.49999916666737499959},
                        {1e-3, 0.49983337499166805536, 0.49916737459184576966},
                        {0.1, 0.48374180359595731642, 0.42335896501795286273},
                        {0.3, 0.45353578535242073408, 0.30403437510537226278},
                        {0.5, 0.42612263885053369442, 0.21884599182187976484},
                        {2.0, 0.28383382080915317297, 0.020097091642602537753},
                        {10.0, 0.090000453999297624849, 4.5377257072638027399e-7},
                        {1000.0, 0.000999, 0.0}};
  for (const Case& c : cases) {
    EXPECT_LE(relativeError(clampedCosineUpperIntegral(c.lambda), c.upper), 8.0 * kEps) << c.lambda;
    if (c.lower > 0.0) {
      EXPECT_LE(relativeError(clampedCosineLowerIntegral(c.lambda), c.lower), 8.0 * kEps)
          << c.lambda;
    }
  }
  EXPECT_EQ(clampedCosineLowerIntegral(1000.0), 0.0);  // 5e-441 underflows
  const double below = std::nextafter(0.5, 0.0), above = std::nextafter(0.5, 1.0);
  const double jumpU =
      relativeError(clampedCosineUpperIntegral(below), clampedCosineUpperIntegral(above));
  const double jumpL =
      relativeError(clampedCosineLowerIntegral(below), clampedCosineLowerIntegral(above));
  std::printf("Taylor switch at 0.5: relative jump U %.1e, L %.1e\n", jumpU, jumpL);
  EXPECT_LE(jumpU, 1e-12);
  EXPECT_LE(jumpL, 1e-12);
  EXPECT_EQ(clampedCosineUpperIntegral(0.0), 0.5);
  EXPECT_EQ(clampedCosineLowerIntegral(0.0), 0.5);
}

TEST(SgMathDiffuse, MatchesQuadrature) {
  // D = (1/pi) integral G (w . n)^+ against the grid. The bounds are the fit's measured worst
  // cases (a 1.07-ratio lambda grid over [1e-3, 1000] times a 0.02 c grid; the worst points are
  // in the lists below), which differ from section 4.3's claims:
  //  * everywhere: |error| <= 1.6e-3 of the front-facing value D(lambda, 1) = 2 U (worst 1.55e-3
  //    at lambda = 5.4, c = -0.66). The fit interpolates between L and U, so its error scales
  //    with U, not with D: relative to D it is unbounded for back-facing lobes (2.5 at
  //    lambda = 10, c = -0.95, where D = 2e-5, far above 1e-9);
  //  * lambda <= 0.5: relative <= 2.5e-5 (worst 2.25e-5 at lambda = 0.34, c = -0.08); the
  //    section claims 3e-6, which holds only for lambda <= 0.07;
  //  * lambda = 2: relative 9.4e-4 at c = 0 (the claimed 1e-3), 3.3e-3 at c = -0.8;
  //  * front-facing c >= 0, any lambda: relative <= 6.5e-3 (worst 6.42e-3 at lambda = 8.7,
  //    c = 0; 6.35e-3 at lambda = 10, c = 0, the claimed 6e-3);
  //  * lambda = 1000, c = 0: relative 8.7e-6, not the claimed 1.3e-2, which is the error at
  //    c = -0.1 (1.6e-2, D = 1.3e-8).
  struct Check {
    double lambda, cosine, relativeBound;  // relativeBound < 0: only the bound against 2 U
  };
  std::vector<Check> checks;
  const double cosines[] = {-1.0, -0.8, -0.66, -0.5, -0.1, -0.08, 0.0, 0.1, 0.25, 0.5, 0.75, 1.0};
  for (double lambda : {1e-6, 0.01, 0.1, 0.2, 0.336, 0.4, 0.5})
    for (double c : cosines) checks.push_back({lambda, c, 2.5e-5});
  for (double lambda : {0.7, 1.0, 2.0, 5.4, 8.66, 10.0, 20.0, 100.0, 1000.0})
    for (double c : cosines) checks.push_back({lambda, c, c >= 0.0 ? 6.5e-3 : -1.0});
  checks.push_back({2.0, 0.0, 1e-3});
  checks.push_back({2.0, -0.8, 3.5e-3});
  checks.push_back({1000.0, 0.0, 1e-5});
  double worstOfFront = 0.0, worstSmall = 0.0, worstFrontFacing = 0.0;
  for (const Check& check : checks) {
    const double numeric = clampedCosineQuadrature(check.lambda, check.cosine);
    const double fit = sgClampedCosineIntegralOverPi(check.lambda, check.cosine);
    const double front = 2.0 * clampedCosineUpperIntegral(check.lambda);
    const double ofFront = std::abs(fit - numeric) / front;
    EXPECT_LE(ofFront, 1.6e-3) << check.lambda << " " << check.cosine;
    worstOfFront = std::max(worstOfFront, ofFront);
    if (check.relativeBound > 0.0) {
      const double relative = relativeError(fit, numeric);
      EXPECT_LE(relative, check.relativeBound) << check.lambda << " " << check.cosine;
      (check.lambda <= 0.5 ? worstSmall : worstFrontFacing) =
          std::max(check.lambda <= 0.5 ? worstSmall : worstFrontFacing, relative);
    }
  }
  std::printf("D fit: worst error %.2e of 2U; relative %.2e (lambda <= 0.5), %.2e (c >= 0)\n",
              worstOfFront, worstSmall, worstFrontFacing);
  std::printf(
      "D fit relative error at c = 0: lambda 2: %.2e, 10: %.2e, 1000: %.2e\n",
      relativeError(sgClampedCosineIntegralOverPi(2.0, 0.0), clampedCosineQuadrature(2.0, 0.0)),
      relativeError(sgClampedCosineIntegralOverPi(10.0, 0.0), clampedCosineQuadrature(10.0, 0.0)),
      relativeError(sgClampedCosineIntegralOverPi(1000.0, 0.0),
                    clampedCosineQuadrature(1000.0, 0.0)));
}

TEST(SgMathDiffuse, WhiteFurnaceAndMonotoneInCosine) {
  // Section 12 case 18: D is normalised per pi, so lambda -> 0 gives (1/pi) integral (w.n)^+ = 1
  // for every c; D = 1 - O(lambda).
  for (double c = -1.0; c <= 1.0; c += 0.125) {
    EXPECT_EQ(sgClampedCosineIntegralOverPi(0.0, c), 1.0) << c;
    // First order, exact: (1/pi) integral (1 + lambda (w . xi - 1)) (w . n)^+ = 1 - lambda +
    // (2/3) lambda c, which the fit reproduces (s = (1 + c) / 2 + O(lambda)).
    const double lambda = 1e-8;
    EXPECT_NEAR(sgClampedCosineIntegralOverPi(lambda, c), 1.0 - lambda * (1.0 - 2.0 * c / 3.0),
                4.0 * kEps)
        << c;
  }
  // A lobe turned away from the normal never receives more (the behind-the-receiver case relies
  // on it): D non-decreasing in c on a fine grid.
  for (double lambda : {1e-3, 0.5, 0.6, kDiffuseSharpness, 10.0, 100.0, 1e4, kMaxSharpness}) {
    double previous = 0.0;
    for (int i = 0; i <= 400; ++i) {
      const double d = sgClampedCosineIntegralOverPi(lambda, -1.0 + double(i) / 200.0);
      EXPECT_GE(d, previous) << lambda << " " << i;
      previous = d;
    }
  }
}

TEST(SgMathDiffuse, FiniteAtGrazingAndExtremeSharpness) {
  const double one = std::nextafter(1.0, 0.0);
  const double lambdas[] = {0.0,
                            1e-300,
                            1e-8,
                            0.5,
                            std::nextafter(0.5, 1.0),
                            2.0,
                            1e3,
                            kMaxSharpness,
                            2.0 * kMaxSharpness,
                            1e200};
  const double cosines[] = {-1.0, -one, -0.5, -1e-300, 0.0, 1e-300, 0.5, one, 1.0};
  for (double lambda : lambdas)
    for (double c : cosines) {
      const double d = sgClampedCosineIntegralOverPi(lambda, c);
      EXPECT_TRUE(std::isfinite(d)) << lambda << " " << c;
      EXPECT_GE(d, 0.0);
      // Bounded by the lobe at the normal, 2 U.
      EXPECT_LE(d, 2.0 * clampedCosineUpperIntegral(lambda) * (1.0 + 4.0 * kEps))
          << lambda << " " << c;
    }
  // The sharp limit: D -> 2 max(c, 0) / lambda (a delta of mass 2 pi / lambda, over pi).
  for (double c : {0.2, 0.7, 1.0})
    EXPECT_LE(
        relativeError(sgClampedCosineIntegralOverPi(kMaxSharpness, c), 2.0 * c / kMaxSharpness),
        1e-6);
}

// ---------------------------------------------------------------------------------------------
// VSGL radiance (section 4.1, 4.3; section 12 cases 12, 13, 18).

TEST(SgMathVsgl, RadianceSgIsTheProductOfEmissionAndSpot) {
  // L_i(w) = E G(w; -xi, lambda) G(w; l/d, d^2 / v) evaluated directly, against the returned SG.
  const glm::dvec3 receiver(0.2, -0.1, 0.4);
  const gpu::VsglLobe lobe =
      makeLobe({1.0, 2.0, 3.0}, 0.05, {-0.2, -0.5, -1.0}, 4.0, {1.0, 2.0, 3.0});
  const glm::dvec3 mean(lobe.meanVariance);
  const glm::dvec3 xi = glm::normalize(glm::dvec3(lobe.axisSharpness));
  const double lambda = lobe.axisSharpness.w, variance = lobe.meanVariance.w;
  const glm::dvec3 l = mean - receiver;
  const double d2 = glm::dot(l, l);
  const VsglIncomingRadiance r = vsglIncomingRadiance(lobe, receiver);
  const glm::dvec3 e = glm::dvec3(lobe.power) / (2.0 * kPi * variance * sgIntegral(lambda));
  EXPECT_LE(relativeError(r.scale.z, e.z), 4.0 * kEps);
  for (glm::dvec3 w : {glm::normalize(l), -xi, glm::normalize(l - 0.3 * xi),
                       glm::normalize(glm::dvec3(0, 1, 1))}) {
    const double direct =
        sgEvaluate(w, -xi, lambda) * sgEvaluate(w, glm::normalize(l), d2 / variance);
    EXPECT_LE(relativeError(sgEvaluate(r.sg, w), direct), 1e-12);
  }
}

TEST(SgMathVsgl, ReceiverAtTheMeanIsFinite) {
  // Section 12 case 12: d = 0 gives lambda_x = 0, so the radiance is E G(w; -xi, lambda); with
  // v = 0 as well (a point light at the receiver) only the variance floor keeps it finite.
  const glm::dvec3 mean(1.0, 2.0, 3.0);
  const glm::dvec3 normal = glm::normalize(glm::dvec3(0.1, 0.2, 1.0));
  for (double variance : {0.0, 1e-3})
    for (double lambda : {0.0, kDiffuseSharpness, kMaxSharpness}) {
      const gpu::VsglLobe lobe =
          makeLobe(mean, variance, {0.3, 0.0, -1.0}, lambda, {1.0, 1.0, 1.0});
      const glm::dvec3 xi = glm::normalize(glm::dvec3(lobe.axisSharpness));
      const VsglIncomingRadiance r = vsglIncomingRadiance(lobe, glm::dvec3(lobe.meanVariance));
      EXPECT_DOUBLE_EQ(r.sg.sharpness, double(lobe.axisSharpness.w));
      EXPECT_EQ(r.sg.logAmplitude, 0.0);
      EXPECT_NEAR(glm::distance(r.sg.axis, -xi), 0.0, 4.0 * kEps);
      EXPECT_TRUE(isFinite(r.scale) && r.scale.x > 0.0) << variance << " " << lambda;
      const glm::dvec3 diffuse =
          vsglDiffuseRadiance(lobe, glm::dvec3(lobe.meanVariance), normal, glm::dvec3(0.5));
      EXPECT_TRUE(isFinite(diffuse) && diffuse.x >= 0.0) << variance << " " << lambda;
      // Nearly at the mean (d = 1e-20, d^2 below the FLT_MIN floor): finite as well.
      const glm::dvec3 near = glm::dvec3(lobe.meanVariance) + glm::dvec3(1e-20, 0.0, 0.0);
      EXPECT_TRUE(isFinite(vsglDiffuseRadiance(lobe, near, normal, glm::dvec3(0.5))));
    }
}

TEST(SgMathVsgl, BehindTheReceiverIsSmallButNonNegative) {
  // Section 12 case 13: a VSGL mirrored below the tangent plane (mean and axis reflected in
  // it) receives the SG tail only: >= 0, finite, and <= the front-facing value.
  const glm::dvec3 normal(0.0, 0.0, 1.0);
  const glm::dvec3 mirror(1.0, 1.0, -1.0);
  double worstRatio = 0.0;
  for (double elevation : {1.5, 1.0, 0.5, 0.05})  // angle above the horizon, rad
    for (double variance : {0.0, 1e-4, 0.1, 10.0})
      for (double lambda : {0.0, kDiffuseSharpness, 30.0}) {
        const glm::dvec3 front = 2.0 * glm::dvec3(std::cos(elevation), 0.0, std::sin(elevation));
        // Emitting towards the receiver, tilted sideways.
        const glm::dvec3 axis = glm::normalize(-glm::normalize(front) + glm::dvec3(0.0, 0.3, 0.0));
        const gpu::VsglLobe lit = makeLobe(front, variance, axis, lambda, {1.0, 1.0, 1.0});
        const gpu::VsglLobe behind =
            makeLobe(front * mirror, variance, axis * mirror, lambda, {1.0, 1.0, 1.0});
        const double a = vsglDiffuseRadiance(lit, {0.0, 0.0, 0.0}, normal, glm::dvec3(1.0)).x;
        const double b = vsglDiffuseRadiance(behind, {0.0, 0.0, 0.0}, normal, glm::dvec3(1.0)).x;
        EXPECT_TRUE(std::isfinite(a) && std::isfinite(b));
        EXPECT_GE(b, 0.0);
        EXPECT_LE(b, a) << elevation << " " << variance << " " << lambda;
        worstRatio = std::max(worstRatio, b / a);
      }
  std::printf("behind / front diffuse: largest ratio %.3f\n", worstRatio);
}

TEST(SgMathVsgl, FarFieldEqualsPointLight) {
  // Section 12 case 18: as v / d^2 -> 0 the VSGL is a point light of intensity
  // I(-l^) = Phi G(-l^; xi, lambda) / S(lambda), so the diffuse radiance is
  // rho / pi I cos / d^2. Checks the 1/pi convention of D and the 1/(2 pi v) of E together.
  const glm::dvec3 receiver(0.1, -0.2, 0.05);
  const glm::dvec3 normal = glm::normalize(glm::dvec3(0.2, 0.1, 1.0));
  const Frame frame = frameAround(normal);
  const glm::dvec3 albedo(0.8, 0.5, 0.2), power(3.0, 2.0, 1.0);
  double worst = 0.0;
  for (double cosine : {0.95, 0.5, 0.1})
    for (double variance : {0.0, 1e-12, 1e-4})
      for (double lambda : {0.0, kDiffuseSharpness, 50.0}) {
        const glm::dvec3 direction =
            cosine * normal + std::sqrt(1.0 - cosine * cosine) * frame.tangent;
        // Emitting back towards the receiver, 0.3 rad off.
        const glm::dvec3 axis = glm::normalize(-direction + 0.3 * frame.bitangent);
        const gpu::VsglLobe lobe =
            makeLobe(receiver + 10.0 * direction, variance, axis, lambda, power);
        const glm::dvec3 l = glm::dvec3(lobe.meanVariance) - receiver;
        const double d = glm::length(l);
        const glm::dvec3 lHat = l / d;
        const glm::dvec3 xi = glm::normalize(glm::dvec3(lobe.axisSharpness));
        const double sharpness = lobe.axisSharpness.w;
        const glm::dvec3 intensity =
            glm::dvec3(lobe.power) * sgEvaluate(-lHat, xi, sharpness) / sgIntegral(sharpness);
        const glm::dvec3 expected = albedo / kPi * intensity * glm::dot(normal, lHat) / (d * d);
        const glm::dvec3 got = vsglDiffuseRadiance(lobe, receiver, normal, albedo);
        for (int i = 0; i < 3; ++i) {
          const double error = relativeError(got[i], expected[i]);
          EXPECT_LE(error, 1e-3) << cosine << " " << variance << " " << lambda;
          worst = std::max(worst, error);
        }
      }
  std::printf("far-field VSGL vs point light: worst relative error %.2e\n", worst);
}

}  // namespace
}  // namespace gi
