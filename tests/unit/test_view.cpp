// Projection and view conventions (docs/architecture.md): Vulkan clip space with NDC y down and
// depth [0, 1], infinite far planes, orthographic windows, and the shadow views of each light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/direct_light.h"
#include "engine/view.h"

namespace {

glm::vec3 project(const glm::mat4& m, const glm::vec3& p) {
  glm::vec4 c = m * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

TEST(View, PerspectiveMapsNearToZeroFarToOneAndYDown) {
  glm::mat4 p = engine::perspectiveVulkan(1.0f, 2.0f, 0.5f, 20.0f);
  EXPECT_NEAR(project(p, {0, 0, -0.5f}).z, 0.0f, 1e-6f);
  EXPECT_NEAR(project(p, {0, 0, -20.0f}).z, 1.0f, 1e-6f);
  // A point above the axis lands in the top half of the image: negative NDC y.
  EXPECT_LT(project(p, {0, 1, -5}).y, 0.0f);
  // The top edge of the vertical field of view is NDC y = -1; aspect 2 halves x.
  float t = std::tan(0.5f);
  EXPECT_NEAR(project(p, {0, 5 * t, -5}).y, -1.0f, 1e-5f);
  EXPECT_NEAR(project(p, {10 * t, 0, -5}).x, 1.0f, 1e-5f);
}

TEST(View, InfinitePerspectiveApproachesOne) {
  glm::mat4 p = engine::perspectiveVulkan(1.0f, 1.0f, 0.1f, 0.0f);
  EXPECT_NEAR(project(p, {0, 0, -0.1f}).z, 0.0f, 1e-6f);
  float zFar = project(p, {0, 0, -1e6f}).z;
  EXPECT_LT(zFar, 1.0f);
  EXPECT_GT(zFar, 0.999999f);
  // Depth grows monotonically with distance.
  EXPECT_LT(project(p, {0, 0, -1}).z, project(p, {0, 0, -2}).z);
}

TEST(View, OrthographicWindow) {
  glm::mat4 p = engine::orthographicVulkan(2.0f, 1.0f, 1.0f, 11.0f);
  glm::vec3 a = project(p, {2.0f, 1.0f, -1.0f});
  EXPECT_NEAR(a.x, 1.0f, 1e-6f);
  EXPECT_NEAR(a.y, -1.0f, 1e-6f);  // +y up in view space is the top of the image
  EXPECT_NEAR(a.z, 0.0f, 1e-6f);
  EXPECT_NEAR(project(p, {0, 0, -11.0f}).z, 1.0f, 1e-6f);
}

TEST(View, LookAlongIsRigidAndLooksDownMinusZ) {
  glm::vec3 eye(1, 2, 3), forward = glm::normalize(glm::vec3(1, -1, -2));
  glm::mat4 v = engine::lookAlong(eye, forward, {0, 1, 0});
  EXPECT_NEAR(glm::length(glm::vec3(v * glm::vec4(eye, 1))), 0.0f, 1e-5f);
  glm::vec3 ahead = glm::vec3(v * glm::vec4(eye + 2.0f * forward, 1));
  EXPECT_NEAR(ahead.x, 0.0f, 1e-5f);
  EXPECT_NEAR(ahead.y, 0.0f, 1e-5f);
  EXPECT_NEAR(ahead.z, -2.0f, 1e-5f);
  glm::mat3 r(v);
  glm::mat3 shouldBeIdentity = glm::transpose(r) * r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(shouldBeIdentity[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
}

TEST(View, CameraScaleIsIgnoredAndViewportAspectUsed) {
  engine::Camera c;
  c.cameraToWorld = glm::mat4(1.0f);
  c.cameraToWorld[0] *= 3.0f;  // a scaled camera node must not squash the image
  c.cameraToWorld[3] = glm::vec4(0, 0, 5, 1);
  c.yfov = 0.9f;
  engine::View view = engine::cameraView(c, 200, 100);
  glm::vec3 centre = project(view.viewProj, {0, 0, 0});
  EXPECT_NEAR(centre.x, 0.0f, 1e-6f);
  EXPECT_NEAR(centre.y, 0.0f, 1e-6f);
  float t = std::tan(0.45f);
  EXPECT_NEAR(project(view.viewProj, {2.0f * 5.0f * t, 0, 0}).x, 1.0f, 1e-5f);
  glm::vec3 roundTrip = project(view.invViewProj, project(view.viewProj, {0.3f, -0.2f, 1.0f}));
  EXPECT_NEAR(glm::length(roundTrip - glm::vec3(0.3f, -0.2f, 1.0f)), 0.0f, 1e-4f);
}

engine::Scene sceneWith(const engine::Light& light) {
  engine::Scene s;
  s.positions = {{-1, 0, -1}, {1, 0, -1}, {0, 0, 1}};
  s.indices = {0, 1, 2};
  s.lights = {light};
  return s;
}

// A spot 2 m above the origin pointing down, inner cone 0.3 rad, outer 0.5 rad.
engine::Light downwardSpot() {
  engine::Light spot;
  spot.type = engine::LightType::Spot;
  spot.position = {0, 2, 0};
  spot.direction = {0, -1, 0};
  spot.innerConeAngle = 0.3f;
  spot.outerConeAngle = 0.5f;
  return spot;
}

TEST(LightSetup, ViewsPerLightType) {
  engine::Light spot = downwardSpot();
  EXPECT_EQ(engine::buildLightSetup(sceneWith(spot), {256, true}).views.size(), 1u);
  spot.outerConeAngle = 1.5f;  // too wide for one perspective view
  EXPECT_EQ(engine::buildLightSetup(sceneWith(spot), {256, true}).views.size(), 6u);
  engine::Light point = spot;
  point.type = engine::LightType::Point;
  EXPECT_EQ(engine::buildLightSetup(sceneWith(point), {256, true}).views.size(), 6u);
  engine::Light sun = spot;
  sun.type = engine::LightType::Directional;
  auto setup = engine::buildLightSetup(sceneWith(sun), {256, true});
  ASSERT_EQ(setup.views.size(), 1u);
  EXPECT_EQ(setup.lights[0].info.z, 1u);
  EXPECT_TRUE(engine::buildLightSetup(sceneWith(sun), {256, false}).views.empty());
}

// A shadow map given from elsewhere (the module's light view) gets the texel size the host's
// own view of the same matrix has: 2 tan(half angle) / resolution per metre for a perspective
// view, 2 half-extent / resolution for an orthographic one.
TEST(LightSetup, GivenShadowViewHasTheTexelOfItsMatrix) {
  engine::Light spot = downwardSpot();
  engine::Light point = spot;
  point.type = engine::LightType::Point;
  engine::Light sun = spot;
  sun.type = engine::LightType::Directional;
  for (const engine::Light& light : {spot, point, sun}) {
    const auto setup = engine::buildLightSetup(sceneWith(light), {256, true});
    for (const gpu::ShadowView& own : setup.views) {
      const gpu::ShadowView given = engine::givenShadowView(own.viewProj, 256);
      EXPECT_EQ(given.viewProj, own.viewProj);
      EXPECT_NEAR(given.texel.x, own.texel.x, 1e-5f * own.texel.x);
      EXPECT_NEAR(given.texel.y, own.texel.y, 1e-5f * own.texel.y);
      EXPECT_GT(given.texel.x + given.texel.y, 0.0f);
    }
  }
}

TEST(LightSetup, ShadowViewsSeeTheSceneAndSpotFalloffMatchesTheExtension) {
  auto setup = engine::buildLightSetup(sceneWith(downwardSpot()), {256, true});
  // The triangle below the spot projects inside the view and within the depth range.
  glm::vec3 ndc = project(setup.views[0].viewProj, {0, 0, 0});
  EXPECT_LT(std::abs(ndc.x), 1.0f);
  EXPECT_LT(std::abs(ndc.y), 1.0f);
  EXPECT_GT(ndc.z, 0.0f);
  EXPECT_LT(ndc.z, 1.0f);
  // KHR_lights_punctual: falloff = saturate(cos * scale + offset)^2, 1 inside the inner cone and
  // 0 at the outer cone.
  const auto& s = setup.lights[0].spot;
  auto falloff = [&](float angle) {
    float t = std::clamp(std::cos(angle) * s.x + s.y, 0.0f, 1.0f);
    return t * t;
  };
  EXPECT_NEAR(falloff(0.3f), 1.0f, 1e-5f);
  EXPECT_NEAR(falloff(0.5f), 0.0f, 1e-5f);
  EXPECT_GT(falloff(0.4f), 0.0f);
  EXPECT_LT(falloff(0.4f), 1.0f);
}

}  // namespace
