#include "reference/env_paraboloid.h"

#include <cmath>
#include <numbers>

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

ParaboloidCoordinates paraboloidFromDirection(glm::dvec3 direction) {
  const uint32_t map = direction.z >= 0.0 ? 0u : 1u;
  return {map, paraboloidCoordinatesInMap(direction, map)};
}

double paraboloidMapZ(glm::dvec3 direction, uint32_t map) {
  return map == 0 ? direction.z : -direction.z;
}

glm::dvec2 paraboloidCoordinatesInMap(glm::dvec3 direction, uint32_t map) {
  // (x, y) / (1 + z_m): the stereographic projection from the map's antipode, scaled by 1 / b
  // and centred. In the map's own hemisphere 1 + z_m >= 1, so there is no cancellation; in the
  // other one it is fine down to z_m = -0.485 (the square's corners).
  const double denominator = 2.0 * kParaboloidScale * (1.0 + paraboloidMapZ(direction, map));
  return glm::dvec2(0.5) + glm::dvec2(direction.x, direction.y) / denominator;
}

glm::dvec3 paraboloidToDirection(glm::dvec2 st, uint32_t map) {
  // Inverse stereographic projection of (u, v) = b (2 st - 1): (2 u, 2 v, 1 - rho^2) / (1 + rho^2).
  const glm::dvec2 uv = kParaboloidScale * (2.0 * st - 1.0);
  const double rho2 = glm::dot(uv, uv);
  const double inv = 1.0 / (1.0 + rho2);
  const double mapZ = (1.0 - rho2) * inv;
  return {2.0 * uv.x * inv, 2.0 * uv.y * inv, map == 0 ? mapZ : -mapZ};
}

double paraboloidSolidAnglePerArea(double mapZ) {
  const double onePlusZ = 1.0 + mapZ;
  return 4.0 * kParaboloidScale * kParaboloidScale * onePlusZ * onePlusZ;
}

double paraboloidSolidAnglePerArea(glm::dvec2 st) {
  // Written in rho instead of z_m so that the corners (z_m near -1/2) lose nothing to 1 + z_m.
  const glm::dvec2 uv = kParaboloidScale * (2.0 * st - 1.0);
  const double onePlusRho2 = 1.0 + glm::dot(uv, uv);
  return 16.0 * kParaboloidScale * kParaboloidScale / (onePlusRho2 * onePlusRho2);
}

glm::dvec2 equirectFromDirection(glm::dvec3 direction) {
  // atan2 of (sin, cos) rather than acos(y): acos loses half the digits next to the poles.
  const double horizontal = std::hypot(direction.x, direction.z);
  const double theta = std::atan2(horizontal, direction.y);
  double phi = std::atan2(direction.z, direction.x);  // (-pi, pi]
  if (phi < 0.0) phi += 2.0 * kPi;
  double u = phi / (2.0 * kPi);
  if (u >= 1.0) u = 0.0;  // phi = -tiny rounds to 2 pi
  return {u, theta / kPi};
}

glm::dvec3 equirectToDirection(glm::dvec2 uv) {
  const double theta = kPi * uv.y, phi = 2.0 * kPi * uv.x;
  const double sinTheta = std::sin(theta);
  return {sinTheta * std::cos(phi), std::cos(theta), sinTheta * std::sin(phi)};
}

double equirectSolidAnglePerArea(double v) {
  return 2.0 * kPi * kPi * std::sin(kPi * v);
}

double equirectTexelSolidAngle(uint32_t row, uint32_t width, uint32_t height) {
  // cos theta_0 - cos theta_1 = 2 sin(mean) sin(half width): no cancellation at the poles.
  const double theta0 = kPi * row / height, theta1 = kPi * (row + 1.0) / height;
  const double band = 2.0 * std::sin(0.5 * (theta0 + theta1)) * std::sin(0.5 * (theta1 - theta0));
  return 2.0 * kPi / width * band;
}

}  // namespace gi
