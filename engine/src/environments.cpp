#include "engine/environments.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "engine/error.h"

namespace engine {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

using Radiance = std::function<glm::dvec3(double theta, double phi, glm::dvec3 direction)>;

glm::dvec3 sky(double /*theta*/, double /*phi*/, glm::dvec3 d) {
  const glm::dvec3 sun(kSkySunDirection);
  if (glm::dot(d, glm::normalize(sun)) >= std::cos(double(kSkySunAngularRadius)))
    return glm::dvec3(kSkySunRadiance);
  if (d.y < 0.0) return glm::dvec3(kSkyGround);
  // Smooth in the elevation: 1 - (1 - y)^2 rises fast above the horizon, flat at the zenith.
  const double t = 1.0 - (1.0 - d.y) * (1.0 - d.y);
  return glm::mix(glm::dvec3(kSkyHorizon), glm::dvec3(kSkyZenith), t);
}

// A rectangle in (phi, theta), degrees, with its radiance.
struct AreaLight {
  double phi0, phi1, theta0, theta1;
  glm::dvec3 radiance;
};

glm::dvec3 studio(double theta, double phi, glm::dvec3 d) {
  static const AreaLight kLights[] = {
      {20.0, 50.0, 50.0, 75.0, {40.0, 40.0, 38.0}},    // key light, in front and above
      {200.0, 240.0, 60.0, 80.0, {9.0, 10.0, 12.0}},   // fill light, opposite, bluish
      {100.0, 160.0, 10.0, 25.0, {20.0, 20.0, 20.0}},  // top light, off the pole
  };
  const double phiDeg = phi / kDegree, thetaDeg = theta / kDegree;
  for (const AreaLight& light : kLights)
    if (phiDeg >= light.phi0 && phiDeg < light.phi1 && thetaDeg >= light.theta0 &&
        thetaDeg < light.theta1)
      return light.radiance;
  // The checker band: 128 cells around, cells of 360/128 = 2.8125 degrees in theta too, from
  // theta = 84.375 to 95.625 degrees (4 rows, symmetric about the horizon).
  constexpr double kCell = 360.0 / 128.0;
  if (std::abs(thetaDeg - 90.0) < 2.0 * kCell) {
    const int column = static_cast<int>(std::floor(phiDeg / kCell));
    const int row = static_cast<int>(std::floor((thetaDeg - 90.0) / kCell));
    return ((column + row) & 1) == 0 ? glm::dvec3(1.2) : glm::dvec3(0.01);
  }
  if (d.y > 0.7) return glm::dvec3(0.02);   // ceiling
  if (d.y < -0.3) return glm::dvec3(0.05);  // floor
  return glm::dvec3(0.03);                  // walls
}

glm::dvec3 white(double, double, glm::dvec3) {
  return glm::dvec3(1.0);
}

struct Builtin {
  const char* name;
  glm::dvec3 (*radiance)(double, double, glm::dvec3);
};

constexpr Builtin kBuiltins[] = {{"sky", sky}, {"studio", studio}, {"white", white}};

}  // namespace

std::vector<std::string> builtinEnvironmentNames() {
  std::vector<std::string> names;
  for (const Builtin& builtin : kBuiltins) names.emplace_back(builtin.name);
  return names;
}

ImageRgba32f makeBuiltinEnvironment(const std::string& name, uint32_t width) {
  const Builtin* found = nullptr;
  for (const Builtin& builtin : kBuiltins)
    if (name == builtin.name) found = &builtin;
  if (!found) {
    std::string list;
    for (const Builtin& builtin : kBuiltins)
      list += (list.empty() ? "" : ", ") + std::string(builtin.name);
    throw Error("environment '" + name + "' is not a built-in environment (one of " + list + ")");
  }
  if (width < 4 || width > 16384 || width % 2 != 0)
    throw Error("environment '" + name + "': width " + std::to_string(width) +
                " is not an even number in [4, 16384]");
  ImageRgba32f image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(width / 2);
  image.pixels.resize(size_t{width} * (width / 2) * 4);
  for (uint32_t row = 0; row < width / 2; ++row)
    for (uint32_t column = 0; column < width; ++column) {
      // The texel centre: (u, v) = ((column + 1/2) / w, (row + 1/2) / h), theta = pi v,
      // phi = 2 pi u, direction (sin theta cos phi, cos theta, sin theta sin phi).
      const double theta = kPi * (row + 0.5) / (width / 2);
      const double phi = 2.0 * kPi * (column + 0.5) / width;
      const glm::dvec3 direction(std::sin(theta) * std::cos(phi), std::cos(theta),
                                 std::sin(theta) * std::sin(phi));
      const glm::dvec3 radiance = found->radiance(theta, phi, direction);
      float* pixel = &image.pixels[(size_t{row} * width + column) * 4];
      pixel[0] = static_cast<float>(radiance.r);
      pixel[1] = static_cast<float>(radiance.g);
      pixel[2] = static_cast<float>(radiance.b);
      pixel[3] = 1.0f;
    }
  return image;
}

glm::vec3 environmentRadiance(const ImageRgba32f& equirect, glm::vec3 direction) {
  const int w = equirect.width, h = equirect.height;
  // u = phi / 2 pi from +x towards +z, v = theta / pi from +y; atan2 keeps the poles accurate.
  const float pi = 3.14159265358979f;
  float phi = std::atan2(direction.z, direction.x);
  if (phi < 0.0f) phi += 2.0f * pi;
  const float theta = std::atan2(std::hypot(direction.x, direction.z), direction.y);
  const float px = phi / (2.0f * pi) * float(w) - 0.5f, py = theta / pi * float(h) - 0.5f;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  auto texel = [&](int x, int y) {
    x = ((x % w) + w) % w;
    y = std::clamp(y, 0, h - 1);
    const float* p = &equirect.pixels[(size_t(y) * size_t(w) + size_t(x)) * 4];
    return glm::vec3(p[0], p[1], p[2]);
  };
  const int x0 = int(fx0), y0 = int(fy0);
  const glm::vec3 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx);
  const glm::vec3 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx);
  return glm::mix(top, bottom, fy);
}

}  // namespace engine
