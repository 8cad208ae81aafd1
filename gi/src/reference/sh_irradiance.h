// Irradiance from nine spherical-harmonic coefficients of environment radiance (vsgl-math.md
// section 10, "Diffuse"), in double and naive on purpose: the oracle for the diffuse part of
// environment lighting.
//
// This work is based on:
//   [RH01] Ramamoorthi and Hanrahan, "An Efficient Representation for Irradiance Environment
//          Maps", SIGGRAPH 2001 (Eqs. 3, 8-10: the real basis up to l = 2, the clamped-cosine
//          band weights A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4, E = sum A_l L_lm Y_lm).
//
// Basis. Real SH in Cartesian form on unit directions (x, y, z), WITHOUT the Condon-Shortley
// phase (as in [RH01] and most graphics code), orthonormal over the sphere, indexed
// i = l (l + 1) + m:
//   Y_0  = 1/2 sqrt(1/pi),
//   Y_1..3 = sqrt(3 / (4 pi)) (y, z, x),
//   Y_4..8 = 1/2 sqrt(15/pi) x y, 1/2 sqrt(15/pi) y z, 1/4 sqrt(5/pi) (3 z^2 - 1),
//            1/2 sqrt(15/pi) x z, 1/4 sqrt(15/pi) (x^2 - y^2).
// The irradiance formula is rotation invariant, so the frame of the directions (z up here, y up
// in the equirect map of env_paraboloid.h) does not matter as long as projection and evaluation
// use the same one.
//
// Accuracy of the nine terms (this file's numbers, checked in tests/unit/test_env_math.cpp): the
// clamped-cosine kernel has A_3 = 0 and |A_l| <= 0.131 (l = 4) beyond, so the band-limited E is
// exact for lighting of bands <= 3 and close for smooth lighting. For lighting max(a . w, 0)
// (one clamped-cosine lobe) the exact irradiance is (2/3) ((pi - g) cos g + sin g), g the angle
// between n and a, and the nine terms give pi/4 + (pi/3) cos g + (5 pi / 64) P_2(cos g): error
// exactly pi / 192 = 0.0164 at g = 0 and g = pi (0.78 % of the peak 2 pi / 3, negative ringing
// at g = pi), RMS over the sphere 0.00415 (0.53 % of the mean pi / 4).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <span>

namespace gi {

constexpr int kShCoefficientCount = 9;
using ShBasis = std::array<double, kShCoefficientCount>;
using ShRgb = std::array<glm::dvec3, kShCoefficientCount>;  // coefficients L_lm of RGB radiance

// The nine basis values at a unit direction.
ShBasis shBasis(glm::dvec3 direction);

// One sample of a radiance function: L(direction) and the solid angle it stands for, so that
// sum weight f(direction) approximates the integral of f over the sphere (e.g. texel solid
// angles of an environment map, or quadrature weights).
struct RadianceSample {
  glm::dvec3 direction{0.0, 0.0, 1.0};  // unit
  glm::dvec3 radiance{0.0};
  double solidAngle = 0.0;  // [sr]
};

// L_lm = sum weight L Y_lm(direction) ([RH01] Eq. 3 as a quadrature).
ShRgb shProjectRadiance(std::span<const RadianceSample> samples);

// The band-limited radiance sum L_lm Y_lm(direction).
glm::dvec3 shEvaluate(const ShRgb& coefficients, glm::dvec3 direction);

// [RH01] band weights of the clamped cosine: A_l = 2 pi integral_0^1 t P_l(t) dt.
constexpr double kShIrradianceBand0 = 3.14159265358979323846;              // pi
constexpr double kShIrradianceBand1 = 2.0 * 3.14159265358979323846 / 3.0;  // 2 pi / 3
constexpr double kShIrradianceBand2 = 3.14159265358979323846 / 4.0;        // pi / 4

// E(n) = sum_l A_l sum_m L_lm Y_lm(n) ([RH01] Eq. 8): the irradiance integral of
// L(w) max(n . w, 0) dw with L band-limited to l <= 2. A constant radiance L gives pi L. n unit.
// Divide by pi for the outgoing radiance of a white Lambertian surface.
glm::dvec3 shIrradiance(const ShRgb& coefficients, glm::dvec3 normal);

}  // namespace gi
