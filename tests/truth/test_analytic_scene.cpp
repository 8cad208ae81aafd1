#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "analytic_scene.h"
#include "engine/scene.h"

namespace {

using truth::AnalyticSceneParams;

// Wall points in view of the default camera: low near the lit disc, mid-height off-centre, high
// near a side edge.
const glm::dvec3 kWallPoints[] = {{1.5, 0.3, 0.0}, {1.5, 1.0, 0.8}, {1.5, 1.6, -1.5}};

glm::dvec3 towardsCamera(const AnalyticSceneParams& p, glm::dvec3 x) {
  return glm::normalize(p.cameraEye - x);
}

double relativeDifference(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

// The Lambert-only one-bounce radiance (luminance-free: grey albedos, white light) by the
// midpoint rule on a cells x cells Cartesian grid over the lit disc's bounding square, written
// from the integral in analytic_scene.h without the library's code: the spot's falloff from the
// cone angles in double, the floor's irradiance I falloff cos_l / |s - q|^2.
double lambertOnlyMidpoint(const AnalyticSceneParams& p, glm::dvec3 x, int cells) {
  const double h = p.lightHeight;
  const double radius = h * std::tan(p.outerConeAngle);
  const double cell = 2.0 * radius / cells;
  const double cosOuter = std::cos(p.outerConeAngle);
  const double cosInner = std::cos(p.innerConeAngle);
  double sum = 0.0;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const glm::dvec3 q(-radius + (i + 0.5) * cell, 0.0, -radius + (j + 0.5) * cell);
      const double toLight = glm::length(glm::dvec3(0.0, h, 0.0) - q);
      const double cosAxis = h / toLight;
      const double t = std::clamp((cosAxis - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
      const double floorIrradiance = p.intensity * t * t * cosAxis / (toLight * toLight);
      const double floorRadiance = p.floorAlbedo / std::numbers::pi * floorIrradiance;
      const double d = glm::length(x - q);
      const double cosQ = x.y / d;
      const double cosW = (x.x - q.x) / d;
      sum += p.wallAlbedo / std::numbers::pi * floorRadiance * cosQ * cosW / (d * d);
    }
  }
  return sum * cell * cell;
}

TEST(AnalyticScene, OneBounceConvergedInNodeCount) {
  const AnalyticSceneParams coarse;
  AnalyticSceneParams fine;
  fine.radialNodes = 2 * coarse.radialNodes;
  fine.angularNodes = 2 * coarse.angularNodes;
  for (const glm::dvec3& x : kWallPoints) {
    const glm::dvec3 v = towardsCamera(coarse, x);
    const truth::OneBounceRadiance a = truth::analyticOneBounce(coarse, x, v);
    const truth::OneBounceRadiance b = truth::analyticOneBounce(fine, x, v);
    std::printf("x = (%.2f, %.2f, %.2f): diffuse %.12f glossy %.12f (N) | %.12f %.12f (2N)\n", x.x,
                x.y, x.z, a.diffuse.x, a.glossy.x, b.diffuse.x, b.glossy.x);
    EXPECT_LT(relativeDifference(a.diffuse.x, b.diffuse.x), 1e-6);
    EXPECT_LT(relativeDifference(a.glossy.x, b.glossy.x), 1e-6);
    // Grey albedos, white light, grey F0: the three channels agree.
    EXPECT_EQ(a.diffuse.x, a.diffuse.z);
    EXPECT_EQ(a.glossy.x, a.glossy.y);
    EXPECT_GT(a.glossy.x, 0.0);
    EXPECT_EQ(truth::analyticOneBounceRadiance(coarse, x, v), a.diffuse + a.glossy);
  }
}

TEST(AnalyticScene, MirroredWallPointsAgree) {
  // The scene is symmetric under z -> -z; so are the quadrature's nodes (phi -> 2 pi - phi maps
  // the Gauss-Legendre nodes on [0, 2 pi] onto themselves), hence agreement to rounding.
  const AnalyticSceneParams p;
  const glm::dvec3 points[] = {{1.5, 0.7, 0.9}, {1.5, 1.2, 1.7}};
  const glm::dvec3 views[] = {glm::normalize(glm::dvec3(-1.0, 0.2, 0.5)),
                              glm::normalize(glm::dvec3(-0.3, -0.1, -0.8))};
  for (const glm::dvec3& x : points) {
    for (const glm::dvec3& v : views) {
      const glm::dvec3 mirror(1.0, 1.0, -1.0);
      const glm::dvec3 a = truth::analyticOneBounceRadiance(p, x, v);
      const glm::dvec3 b = truth::analyticOneBounceRadiance(p, x * mirror, v * mirror);
      EXPECT_LT(relativeDifference(a.x, b.x), 1e-12) << a.x << " vs " << b.x;
    }
  }
}

TEST(AnalyticScene, LambertOnlyMatchesCartesianMidpointRule) {
  // 1000^2 cells of 1.37 mm. The midpoint rule's error is O(cell^2): the integrand is smooth
  // except for a kink along the inner cone's circle (the falloff's derivative jumps) and a
  // vanishing one along the outer circle, which cost O(cell^2) as well. Measured: 2.9e-6
  // relative at 250 cells, 6.6e-7 at 500 (the factor 4 of O(cell^2)), so about 1.7e-7 at most
  // at 1000 (2e-8 seen); 1e-6 leaves a margin of 5 and catches any wrong factor. The library's
  // float falloff ramp (engine::spotFalloff) against the double one here adds ~1e-8.
  AnalyticSceneParams p;
  p.lambertOnly = true;
  constexpr int kCells = 1000;
  constexpr double kTolerance = 1e-6;
  for (const glm::dvec3& x : kWallPoints) {
    const double quadrature = truth::analyticOneBounce(p, x, towardsCamera(p, x)).diffuse.x;
    const double midpoint = lambertOnlyMidpoint(p, x, kCells);
    std::printf("x = (%.2f, %.2f, %.2f): Gauss-Legendre %.12f midpoint %.12f\n", x.x, x.y, x.z,
                quadrature, midpoint);
    EXPECT_LT(relativeDifference(quadrature, midpoint), kTolerance);
    EXPECT_EQ(truth::analyticOneBounce(p, x, towardsCamera(p, x)).glossy, glm::dvec3(0.0));
  }
}

TEST(AnalyticScene, FloorDirectRadianceClosedForm) {
  const AnalyticSceneParams p;
  const glm::dvec3 up(0.0, 1.0, 0.0);
  // Below the light, seen from above: n = v = l = h, so GGX at roughness 1 is D = 1 / pi,
  // V = 1 / 4 and F = F0: f = (rho + F0 / 4) / pi, times I / h^2.
  const double centre = (p.floorAlbedo + truth::kAnalyticF0 / 4.0) / std::numbers::pi *
                        p.intensity / (p.lightHeight * p.lightHeight);
  EXPECT_NEAR(truth::analyticFloorDirectRadiance(p, glm::dvec3(0.0), up).x, centre, 1e-12);

  // In the falloff's ramp, Lambert only: rho / pi I t^2 cos / d^2 with cos = h / d; the library
  // takes the ramp from engine::spotFalloff in float, hence the tolerance.
  AnalyticSceneParams lambert = p;
  lambert.lambertOnly = true;
  const glm::dvec3 q(0.4, 0.0, 0.3);
  const double d = std::sqrt(1.0 + 0.25);
  const double cosAxis = p.lightHeight / d;
  const double t = (cosAxis - std::cos(p.outerConeAngle)) /
                   (std::cos(p.innerConeAngle) - std::cos(p.outerConeAngle));
  ASSERT_GT(t, 0.0);
  ASSERT_LT(t, 1.0);
  const double ramp = p.floorAlbedo / std::numbers::pi * p.intensity * t * t * cosAxis / (d * d);
  EXPECT_NEAR(truth::analyticFloorDirectRadiance(lambert, q, up).x, ramp, 1e-6 * ramp);

  // Outside the outer cone: nothing.
  EXPECT_EQ(truth::analyticFloorDirectRadiance(p, glm::dvec3(0.7, 0.0, 0.0), up), glm::dvec3(0.0));
}

TEST(AnalyticScene, BuilderMatchesTheParameters) {
  const AnalyticSceneParams p;
  const engine::Scene scene = truth::makeAnalyticScene(p);
  ASSERT_EQ(scene.triangleCount(), 4u);
  ASSERT_EQ(scene.positions.size(), scene.normals.size());
  ASSERT_EQ(scene.positions.size(), scene.uvs.size());
  EXPECT_EQ(scene.triangleMaterial, (std::vector<uint32_t>{0, 0, 1, 1}));

  // Counter-clockwise front faces towards the stated normals; vertex normals agree.
  const glm::vec3 expectedNormal[] = {{0.0f, 1.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}};
  for (uint32_t t = 0; t < scene.triangleCount(); ++t) {
    const glm::vec3 a = scene.positions[scene.indices[3 * t]];
    const glm::vec3 b = scene.positions[scene.indices[3 * t + 1]];
    const glm::vec3 c = scene.positions[scene.indices[3 * t + 2]];
    const glm::vec3 n = expectedNormal[scene.triangleMaterial[t]];
    EXPECT_GT(glm::dot(glm::normalize(glm::cross(b - a, c - a)), n), 0.9999f) << "triangle " << t;
    for (uint32_t k = 0; k < 3; ++k) EXPECT_EQ(scene.normals[scene.indices[3 * t + k]], n);
  }
  const engine::Bounds bounds = scene.bounds();
  EXPECT_EQ(bounds.min, glm::vec3(-50.0f, 0.0f, -50.0f));
  EXPECT_EQ(bounds.max, glm::vec3(50.0f, 2.0f, 50.0f));
  for (uint32_t i = 4; i < 8; ++i) {  // the wall's vertices
    EXPECT_EQ(scene.positions[i].x, 1.5f);
    EXPECT_EQ(std::abs(scene.positions[i].z), 2.0f);
  }

  ASSERT_EQ(scene.materials.size(), 2u);
  const double albedo[] = {p.floorAlbedo, p.wallAlbedo};
  for (size_t m = 0; m < 2; ++m) {
    EXPECT_EQ(scene.materials[m].baseColorFactor,
              glm::vec4(glm::vec3(static_cast<float>(albedo[m])), 1.0f));
    EXPECT_EQ(scene.materials[m].metallicFactor, 0.0f);
    EXPECT_EQ(scene.materials[m].roughnessFactor, 1.0f);
    EXPECT_EQ(scene.materials[m].baseColorTexture, -1);
    EXPECT_EQ(scene.materials[m].metallicRoughnessTexture, -1);
  }

  ASSERT_EQ(scene.lights.size(), 1u);
  const engine::Light& light = scene.lights[0];
  EXPECT_EQ(light.type, engine::LightType::Spot);
  EXPECT_EQ(light.position, glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(light.direction, glm::vec3(0.0f, -1.0f, 0.0f));
  EXPECT_EQ(light.color, glm::vec3(1.0f));
  EXPECT_EQ(light.intensity, 10.0f);
  EXPECT_EQ(light.range, 0.0f);
  EXPECT_EQ(light.innerConeAngle, 0.45f);
  EXPECT_EQ(light.outerConeAngle, 0.6f);

  // No direct light on the wall: the falloff's ramp is <= 0 at every point of a grid over it.
  const glm::vec2 ramp = engine::spotFalloff(light);
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const glm::vec3 x(1.5f, 0.1f * static_cast<float>(j), -2.0f + 0.1f * static_cast<float>(i));
      const float cosAxis = glm::dot(light.direction, glm::normalize(x - light.position));
      EXPECT_LE(cosAxis * ramp.x + ramp.y, 0.0f) << "wall point " << x.y << ", " << x.z;
    }
  }

  // The camera at the eye looks along +X, and its centre ray meets the wall inside its extent.
  ASSERT_EQ(scene.cameras.size(), 1u);
  const engine::Camera& camera = scene.cameras[0];
  EXPECT_EQ(glm::vec3(camera.cameraToWorld[3]), glm::vec3(-1.0f, 0.6f, 0.0f));
  const glm::vec3 forward = -glm::vec3(camera.cameraToWorld[2]);
  EXPECT_GT(forward.x, 0.999f);
  const glm::vec3 hit =
      camera.cameraToWorld[3] + (1.5f + 1.0f) / forward.x * glm::vec4(forward, 0.0f);
  EXPECT_GT(hit.y, 0.0f);
  EXPECT_LT(hit.y, 2.0f);
  EXPECT_LT(std::abs(hit.z), 2.0f);
  EXPECT_FLOAT_EQ(camera.yfov, 0.9f);
}

}  // namespace
