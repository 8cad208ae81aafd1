#include "analytic_scene.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "engine/brdf_reference.h"

namespace truth {
namespace {

constexpr glm::dvec3 kFloorNormal(0.0, 1.0, 0.0);
constexpr glm::dvec3 kWallNormal(-1.0, 0.0, 0.0);
constexpr glm::dvec3 kSpotDirection(0.0, -1.0, 0.0);

// The spot as the renderer sees it: the scene builder and the oracle both take its falloff from
// this light through engine::spotFalloff, so they agree to the float bit.
engine::Light spotLight(const AnalyticSceneParams& p) {
  engine::Light light;
  light.name = "spot";
  light.type = engine::LightType::Spot;
  light.position = glm::vec3(0.0f, static_cast<float>(p.lightHeight), 0.0f);
  light.direction = glm::vec3(kSpotDirection);
  light.intensity = static_cast<float>(p.intensity);
  light.innerConeAngle = static_cast<float>(p.innerConeAngle);
  light.outerConeAngle = static_cast<float>(p.outerConeAngle);
  return light;
}

// Scale and offset of KHR_lights_punctual's falloff: falloff(cos) = saturate(cos x + y)^2.
glm::dvec2 falloffRamp(const AnalyticSceneParams& p) {
  return glm::dvec2(engine::spotFalloff(spotLight(p)));
}

// The floor radius at which the spot's ramp cos x + y takes `value`: cos = h / sqrt(h^2 + r^2).
double rampRadius(const AnalyticSceneParams& p, glm::dvec2 ramp, double value) {
  const double cosAxis = std::min((value - ramp.y) / ramp.x, 1.0);
  return p.lightHeight * std::sqrt(1.0 / (cosAxis * cosAxis) - 1.0);
}

struct Lobes {
  double diffuse = 0.0;  // rho / pi
  glm::dvec3 specular{0.0};
};

// engine/brdf_reference.h's surface model for unit n, v (to the viewer), l (to the light), as
// common/brdf.glsl's brdfCos splits it (0 when l is below the surface).
Lobes brdf(const AnalyticSceneParams& p, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, double rho) {
  if (glm::dot(n, l) <= 0.0) return {};
  Lobes f;
  f.diffuse = rho / std::numbers::pi;
  if (!p.lambertOnly)
    f.specular = engine::ggxSpecular(n, v, l, glm::dvec3(kAnalyticF0), 1.0, kAnalyticRoughness);
  return f;
}

// Gauss-Legendre rule on [-1, 1]: the nodes are the roots of the Legendre polynomial P_n, found
// by Newton's method from the asymptotic guess cos(pi (i + 3/4) / (n + 1/2)), with
// P_n' = n (x P_n - P_{n-1}) / (x^2 - 1); the weights are 2 / ((1 - x^2) P_n'(x)^2) (Abramowitz
// and Stegun 25.4.29). The rule is symmetric, so only the positive roots are searched.
struct Rule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

Rule gaussLegendre(int n) {
  assert(n >= 1);
  Rule rule;
  rule.nodes.resize(static_cast<size_t>(n));
  rule.weights.resize(static_cast<size_t>(n));
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      // P_n(x) and P_{n-1}(x) by Bonnet's recurrence k P_k = (2k - 1) x P_{k-1} - (k - 1) P_{k-2}.
      double previous = 1.0;
      double current = x;
      for (int k = 2; k <= n; ++k) {
        const double next = ((2 * k - 1) * x * current - (k - 1) * previous) / k;
        previous = std::exchange(current, next);
      }
      derivative = n * (x * current - previous) / (x * x - 1.0);
      const double step = current / derivative;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
    const auto low = static_cast<size_t>(i);
    const auto high = static_cast<size_t>(n - 1 - i);
    rule.nodes[low] = -x;
    rule.nodes[high] = x;
    rule.weights[low] = weight;
    rule.weights[high] = weight;
  }
  return rule;
}

void addQuad(engine::Scene& scene, glm::dvec3 corner, glm::dvec3 edgeU, glm::dvec3 edgeV,
             uint32_t material) {
  // Counter-clockwise seen from the side cross(edgeU, edgeV) points to.
  const glm::vec3 normal(glm::normalize(glm::cross(edgeU, edgeV)));
  const auto base = static_cast<uint32_t>(scene.positions.size());
  const glm::dvec3 corners[] = {corner, corner + edgeU, corner + edgeU + edgeV, corner + edgeV};
  const glm::vec2 uvs[] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  for (int i = 0; i < 4; ++i) {
    scene.positions.emplace_back(corners[i]);
    scene.normals.push_back(normal);
    scene.uvs.push_back(uvs[i]);
  }
  scene.indices.insert(scene.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  scene.triangleMaterial.insert(scene.triangleMaterial.end(), 2, material);
}

engine::Material roughDielectric(const std::string& name, double albedo) {
  engine::Material material;
  material.name = name;
  material.baseColorFactor = glm::vec4(glm::vec3(static_cast<float>(albedo)), 1.0f);
  material.metallicFactor = 0.0f;
  material.roughnessFactor = static_cast<float>(kAnalyticRoughness);
  return material;
}

engine::Camera lookAtCamera(const AnalyticSceneParams& p) {
  // The camera looks down its local -Z with +Y up (glTF): columns right, up, -forward, eye.
  const glm::vec3 eye(p.cameraEye);
  const glm::vec3 forward = glm::normalize(glm::vec3(p.cameraTarget) - eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::cross(right, forward);
  engine::Camera camera;
  camera.name = "camera";
  camera.cameraToWorld = glm::mat4(glm::vec4(right, 0.0f), glm::vec4(up, 0.0f),
                                   glm::vec4(-forward, 0.0f), glm::vec4(eye, 1.0f));
  camera.yfov = static_cast<float>(p.cameraYfov);
  return camera;
}

}  // namespace

engine::Scene makeAnalyticScene(const AnalyticSceneParams& p) {
  engine::Scene scene;
  scene.source = "builtin:analytic";
  scene.materials = {roughDielectric("floor", p.floorAlbedo),
                     roughDielectric("wall", p.wallAlbedo)};
  const double l = p.floorHalfSize;
  addQuad(scene, {-l, 0.0, l}, {2.0 * l, 0.0, 0.0}, {0.0, 0.0, -2.0 * l}, 0);  // faces +Y
  const double w = p.wallHalfWidth;
  addQuad(scene, {p.wallX, 0.0, -w}, {0.0, 0.0, 2.0 * w}, {0.0, p.wallHeight, 0.0}, 1);  // -X
  scene.lights = {spotLight(p)};
  scene.cameras = {lookAtCamera(p)};
  return scene;
}

glm::dvec3 analyticFloorDirectRadiance(const AnalyticSceneParams& p, glm::dvec3 floorPoint,
                                       glm::dvec3 viewDir) {
  const glm::dvec3 toLight = glm::dvec3(0.0, p.lightHeight, 0.0) - floorPoint;
  const double distance2 = glm::dot(toLight, toLight);
  const glm::dvec3 l = toLight / std::sqrt(distance2);
  const glm::dvec2 ramp = falloffRamp(p);
  const double t = std::clamp(glm::dot(kSpotDirection, -l) * ramp.x + ramp.y, 0.0, 1.0);
  const double irradiance = p.intensity * t * t / distance2;  // at normal incidence
  const Lobes f = brdf(p, kFloorNormal, viewDir, l, p.floorAlbedo);
  return (f.diffuse + f.specular) * glm::dot(kFloorNormal, l) * irradiance;
}

OneBounceRadiance analyticOneBounce(const AnalyticSceneParams& p, glm::dvec3 wallPoint,
                                    glm::dvec3 viewDir) {
  // The wall must lie outside the lit disc: it then gets no direct light and sees all the disc.
  assert(std::tan(p.outerConeAngle) * p.lightHeight < p.wallX);
  const glm::dvec2 ramp = falloffRamp(p);
  const double radii[] = {0.0, rampRadius(p, ramp, 1.0), rampRadius(p, ramp, 0.0)};
  const Rule radial = gaussLegendre(p.radialNodes);
  const Rule angular = gaussLegendre(p.angularNodes);

  OneBounceRadiance sum;
  for (int panel = 0; panel < 2; ++panel) {
    const double centre = 0.5 * (radii[panel] + radii[panel + 1]);
    const double halfWidth = 0.5 * (radii[panel + 1] - radii[panel]);
    for (size_t i = 0; i < radial.nodes.size(); ++i) {
      const double r = centre + halfWidth * radial.nodes[i];
      for (size_t j = 0; j < angular.nodes.size(); ++j) {
        const double phi = std::numbers::pi * (1.0 + angular.nodes[j]);
        const glm::dvec3 q(r * std::cos(phi), 0.0, r * std::sin(phi));
        const glm::dvec3 toWall = wallPoint - q;
        const double distance2 = glm::dot(toWall, toWall);
        const glm::dvec3 wx = toWall / std::sqrt(distance2);
        const double cosQ = glm::dot(kFloorNormal, wx);
        const double cosW = glm::dot(kWallNormal, -wx);
        if (cosQ <= 0.0 || cosW <= 0.0) continue;
        // dA = r dr dphi; the weights map [-1, 1] to the panel and to [0, 2 pi].
        const double area =
            halfWidth * radial.weights[i] * std::numbers::pi * angular.weights[j] * r;
        const glm::dvec3 incident =
            analyticFloorDirectRadiance(p, q, wx) * cosW * cosQ / distance2 * area;
        const Lobes f = brdf(p, kWallNormal, viewDir, -wx, p.wallAlbedo);
        sum.diffuse += f.diffuse * incident;
        sum.glossy += f.specular * incident;
      }
    }
  }
  return sum;
}

glm::dvec3 analyticOneBounceRadiance(const AnalyticSceneParams& p, glm::dvec3 wallPoint,
                                     glm::dvec3 viewDir) {
  const OneBounceRadiance radiance = analyticOneBounce(p, wallPoint, viewDir);
  return radiance.diffuse + radiance.glossy;
}

std::optional<glm::dvec3> analyticWallHit(const AnalyticSceneParams& p, glm::dvec3 origin,
                                          glm::dvec3 dir) {
  if (dir.x <= 0.0) return std::nullopt;
  const glm::dvec3 point = origin + (p.wallX - origin.x) / dir.x * dir;
  if (point.y < 0.01 || point.y > p.wallHeight || std::abs(point.z) > p.wallHalfWidth)
    return std::nullopt;
  return point;
}

}  // namespace truth
