#include "reference/sh_irradiance.h"

#include <cmath>
#include <numbers>

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;

// The band of coefficient i = l (l + 1) + m.
constexpr int kBandOf[kShCoefficientCount] = {0, 1, 1, 1, 2, 2, 2, 2, 2};
constexpr double kBandWeight[3] = {kShIrradianceBand0, kShIrradianceBand1, kShIrradianceBand2};

}  // namespace

ShBasis shBasis(glm::dvec3 d) {
  // Normalisation constants of [RH01] Eq. 3 (0.282095, 0.488603, 1.092548, 0.315392, 0.546274),
  // computed rather than rounded.
  const double c0 = 0.5 * std::sqrt(1.0 / kPi);
  const double c1 = std::sqrt(3.0 / (4.0 * kPi));
  const double c2 = 0.5 * std::sqrt(15.0 / kPi);
  const double c20 = 0.25 * std::sqrt(5.0 / kPi);
  const double c22 = 0.25 * std::sqrt(15.0 / kPi);
  return {c0,
          c1 * d.y,
          c1 * d.z,
          c1 * d.x,
          c2 * d.x * d.y,
          c2 * d.y * d.z,
          c20 * (3.0 * d.z * d.z - 1.0),
          c2 * d.x * d.z,
          c22 * (d.x * d.x - d.y * d.y)};
}

ShRgb shProjectRadiance(std::span<const RadianceSample> samples) {
  ShRgb coefficients;
  coefficients.fill(glm::dvec3(0.0));
  for (const RadianceSample& sample : samples) {
    const ShBasis y = shBasis(sample.direction);
    for (int i = 0; i < kShCoefficientCount; ++i)
      coefficients[i] += sample.solidAngle * y[i] * sample.radiance;
  }
  return coefficients;
}

glm::dvec3 shEvaluate(const ShRgb& coefficients, glm::dvec3 direction) {
  const ShBasis y = shBasis(direction);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < kShCoefficientCount; ++i) sum += y[i] * coefficients[i];
  return sum;
}

glm::dvec3 shIrradiance(const ShRgb& coefficients, glm::dvec3 normal) {
  // Funk-Hecke: convolving with the zonal clamped cosine scales band l by A_l ([RH01] Eq. 8).
  const ShBasis y = shBasis(normal);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < kShCoefficientCount; ++i)
    sum += kBandWeight[kBandOf[i]] * y[i] * coefficients[i];
  return sum;
}

}  // namespace gi
