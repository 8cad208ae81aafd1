// The ISM CPU twins as math (gi/src/reference/ism_reference.h) and the settings' validation:
// area-proportional stratified points, the frame and the paraboloid map, pull-push on hand-made
// tiles, and the ray cast.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "engine/error.h"
#include "passes/ism.h"
#include "reference/ism_reference.h"

namespace {

// Two triangles in the plane z = 0 with areas 1/2 and 3/2.
const std::vector<glm::vec3> kPositions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                           {2, 0, 0}, {5, 0, 0}, {2, 1, 0}};
const std::vector<uint32_t> kIndices = {0, 1, 2, 3, 4, 5};

TEST(IsmReference, PointsAreStratifiedByAreaAndInsideTheirTriangles) {
  const auto cdf = gi::ismTriangleCdfReference(kPositions, kIndices);
  ASSERT_EQ(cdf.size(), 2u);
  EXPECT_DOUBLE_EQ(cdf[0], 0.5);
  EXPECT_DOUBLE_EQ(cdf[1], 2.0);
  const uint32_t count = 1024;
  const auto points = gi::ismPointsReference(kPositions, kIndices, count);
  uint32_t first = 0;
  glm::dvec2 mean(0.0);
  for (const gi::IsmPointReference& p : points) {
    first += p.triangle == 0;
    EXPECT_GE(p.bary.x, 0.0);
    EXPECT_GE(p.bary.y, 0.0);
    EXPECT_LE(p.bary.x + p.bary.y, 1.0);
    mean += p.bary;
  }
  EXPECT_EQ(first, count / 4);  // exactly a quarter: stratified u, area ratio 1 : 3
  // Uniform in area: the mean barycentric weights are 1/3 each (R2 with 1024 points: ~1e-3).
  mean /= double(count);
  EXPECT_NEAR(mean.x, 1.0 / 3.0, 3e-3);
  EXPECT_NEAR(mean.y, 1.0 / 3.0, 3e-3);
}

TEST(IsmReference, NoAreaGivesNoPoints) {
  const std::vector<glm::vec3> flat = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  for (const auto& p : gi::ismPointsReference(flat, std::vector<uint32_t>{0, 1, 2}, 64))
    EXPECT_EQ(p.triangle, ISM_NO_TRIANGLE);
}

TEST(IsmReference, FrameIsOrthonormalAndTheParaboloidCoversTheHemisphere) {
  for (glm::dvec3 axis : {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::dvec3(0, -1, 0),
                          glm::normalize(glm::dvec3(0.3, -1.0, 0.2))}) {
    gpu::Vsgl v{};
    v.diffuse.meanVariance = glm::vec4(1, 2, 3, 0);
    v.diffuse.axisSharpness = glm::vec4(glm::vec3(axis), 1.0f);
    v.diffuse.power = glm::vec4(1.0f);
    const gi::IsmFrameReference f = gi::ismFrameReference(v, 0.1);
    ASSERT_TRUE(f.lit);
    EXPECT_NEAR(glm::length(f.centre - (glm::dvec3(1, 2, 3) + 0.1 * f.axis)), 0.0, 1e-6);
    EXPECT_NEAR(glm::dot(f.tangent, f.bitangent), 0.0, 1e-6);
    EXPECT_NEAR(glm::dot(f.tangent, f.axis), 0.0, 1e-6);
    EXPECT_NEAR(glm::dot(f.bitangent, f.axis), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(f.tangent), 1.0, 1e-6);
    EXPECT_NEAR(glm::length(f.bitangent), 1.0, 1e-6);
    // The pole maps to the centre of the map, the rim to the inscribed circle.
    const gi::IsmProjection pole = gi::ismProjectReference(f, f.centre + 2.0 * f.axis);
    EXPECT_NEAR(pole.uv.x, 0.5, 1e-6);  // the axis is stored in fp32
    EXPECT_NEAR(pole.uv.y, 0.5, 1e-6);
    EXPECT_NEAR(pole.distance, 2.0, 1e-6);
    const gi::IsmProjection rim = gi::ismProjectReference(f, f.centre + f.tangent + 1e-9 * f.axis);
    EXPECT_NEAR(glm::length(rim.uv - 0.5), 0.5, 1e-6);
  }
  gpu::Vsgl dark{};
  EXPECT_FALSE(gi::ismFrameReference(dark, 0.1).lit);
  // A visibility point moves the centre there (lifted the same way); axis and extent stay the
  // lobes'.
  gpu::Vsgl v{};
  v.diffuse.meanVariance = glm::vec4(1, 2, 3, 0.04f);
  v.diffuse.axisSharpness = glm::vec4(0, 0, 1, 1);
  v.diffuse.power = glm::vec4(1.0f);
  v.visibilityPoint = glm::vec4(1.5f, 2.25f, 3.0f, 1.0f);
  const gi::IsmFrameReference f = gi::ismFrameReference(v, 0.1);
  EXPECT_NEAR(glm::length(f.centre - glm::dvec3(1.5, 2.25, 3.1)), 0.0, 1e-6);
  EXPECT_EQ(f.axis, glm::dvec3(0, 0, 1));
  EXPECT_NEAR(f.extent, 0.2, 1e-7);
}

TEST(IsmReference, PullPushFillsHolesWithinEachTile) {
  const uint32_t size = 16;
  const size_t tile = size * size;
  std::vector<double> raw(3 * tile, gi::kIsmEmptyReference);
  raw[5 * size + 7] = 2.5;  // tile 0: one point
  // tile 1: no point at all; tile 2: a left half at 1 and a right half at 3
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; x += 3) raw[2 * tile + y * size + x] = x < size / 2 ? 1.0 : 3.0;
  const auto out = gi::ismPullPushReference(raw, size, 3);
  for (size_t i = 0; i < tile; ++i) EXPECT_DOUBLE_EQ(out[i], 2.5);
  for (size_t i = tile; i < 2 * tile; ++i) EXPECT_TRUE(std::isinf(out[i]) && out[i] > 0.0);
  for (size_t i = 2 * tile; i < 3 * tile; ++i) {
    EXPECT_GE(out[i], 1.0);
    EXPECT_LE(out[i], 3.0);
    if (raw[i] >= 0.0) {
      EXPECT_EQ(out[i], raw[i]);
    }
  }
  EXPECT_DOUBLE_EQ(out[2 * tile + 4 * size + 1], 1.0);   // deep in the left half
  EXPECT_DOUBLE_EQ(out[2 * tile + 4 * size + 13], 3.0);  // deep in the right half
}

TEST(IsmReference, RayCastSeesTheOccluderAndIgnoresTheReceiver) {
  // A unit quad at z = 1 between z = 0 and z = 2.
  const std::vector<glm::vec3> quad = {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
  EXPECT_FALSE(gi::ismRayCastVisible(quad, idx, {0, 0, 0}, {0.2, 0.3, 2}));
  EXPECT_TRUE(gi::ismRayCastVisible(quad, idx, {0, 0, 0}, {3, 0, 2}));
  EXPECT_TRUE(gi::ismRayCastVisible(quad, idx, {0, 0, 0}, {0.2, 0.3, 1.0}));  // on the quad
  EXPECT_TRUE(gi::ismRayCastVisible(quad, idx, {0, 0, 0}, {0.1, 0.1, 0.5}));  // before it
}

// In the hemisphere the lookup is a depth test with bias. Behind its base plane the map holds
// nothing: the VSGL is seen only within one standard deviation of its extent, fading linearly
// from 1 at the plane (continuous with the lit side) to 0 at that depth.
TEST(IsmReference, LookupTestsDepthWithBiasAndFadesBehindTheBasePlane) {
  const uint32_t size = 16;
  std::vector<double> atlas(size * size, 1.0);  // an occluder 1 m away in every direction
  gpu::Vsgl v{};
  v.diffuse.axisSharpness = glm::vec4(0, 0, 1, 1);
  v.diffuse.power = glm::vec4(1.0f);
  v.diffuse.meanVariance = glm::vec4(0, 0, 0, 0.04f);  // extent 0.2 m
  const gi::IsmFrameReference f = gi::ismFrameReference(v, 0.0);
  ASSERT_NEAR(f.extent, 0.2, 1e-6);
  gpu::IsmParams params{};
  params.mapSize = size;
  params.depthBias = 0.05f;
  for (uint32_t pcf : {ISM_PCF_NEAREST, ISM_PCF_BILINEAR, ISM_PCF_BOX3}) {
    params.pcf = pcf;
    const glm::dvec3 n(0, 0, 1);
    auto visibility = [&](glm::dvec3 p) {
      return gi::ismVisibilityReference(atlas, params, f, 0, p, n);
    };
    EXPECT_EQ(visibility({0.1, 0.2, 2.0}), 0.0);
    EXPECT_NEAR(visibility({0.1, 0.2, 1.02}), 1.0, 1e-12);
    EXPECT_NEAR(visibility({0.1, 0.2, 0.5}), 1.0, 1e-12);
    EXPECT_NEAR(visibility({3.0, 0.0, 0.0}), 1.0, 1e-12);  // on the plane
    // 1e-6: the variance is stored in fp32.
    EXPECT_NEAR(visibility({3.0, 0.0, -0.05}), 0.75, 1e-6);  // a quarter of the extent behind
    EXPECT_NEAR(visibility({0.1, 0.2, -0.1}), 0.5, 1e-6);
    EXPECT_EQ(visibility({0.1, 0.2, -0.21}), 0.0);
    EXPECT_EQ(visibility({0.1, 0.2, -2.0}), 0.0);
  }
  // The extent weights both lobes' variances by their powers; a dark VSGL never shadows.
  v.specular.power = glm::vec4(3.0f);
  v.specular.meanVariance = glm::vec4(0, 0, 0, 0.08f);
  EXPECT_NEAR(gi::ismFrameReference(v, 0.0).extent, std::sqrt(0.25 * 0.04 + 0.75 * 0.08), 1e-7);
  gpu::Vsgl dark{};
  EXPECT_EQ(gi::ismVisibilityReference(atlas, params, gi::ismFrameReference(dark, 0.0), 0,
                                       {0.1, 0.2, -2.0}, {0, 0, 1}),
            1.0);
}

TEST(IsmSettings, DefaultsAreValidAndEachBadFieldIsNamed) {
  EXPECT_NO_THROW(gi::validateIsmSettings({}));
  auto expectError = [](gi::IsmSettings s, const std::string& field) {
    try {
      gi::validateIsmSettings(s);
      ADD_FAILURE() << field << " accepted";
    } catch (const engine::Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  gi::IsmSettings s;
  s.mapSize = 48;
  expectError(s, "mapSize");
  s = {};
  s.mapSize = 512;
  expectError(s, "mapSize");
  s = {};
  s.pointCount = 1000;
  expectError(s, "pointCount");
  s = {};
  s.pointsPerVsgl = s.pointCount * 2;
  expectError(s, "pointsPerVsgl");
  s = {};
  s.depthBias = -1.0f;
  expectError(s, "depthBias");
  s = {};
  s.slopeBias = std::numeric_limits<float>::quiet_NaN();
  expectError(s, "slopeBias");
  s = {};
  s.centreOffset = 20.0f;
  expectError(s, "centreOffset");
  s = {};
  s.pcf = ISM_MAX_PCF + 1;
  expectError(s, "pcf");
}

}  // namespace
