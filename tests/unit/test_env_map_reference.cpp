// The CPU twin of the environment conversion (gi/src/reference/env_map_reference.h) and the
// built-in environments (engine/environments.h), tested as math: constant radiance converts to
// constants exactly, mips are exact means, the bilinear equirect read wraps in u and clamps in v,
// the SH projection's solid angles sum to 4 pi within the rim's staircase error and project
// band-1 radiance onto its analytic coefficients, and the built-in images are finite,
// non-negative and hold the stated sun radiance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "engine/environments.h"
#include "engine/error.h"
#include "reference/env_map_reference.h"
#include "reference/env_paraboloid.h"
#include "reference/sh_irradiance.h"

namespace gi {
namespace {

constexpr double kPi = std::numbers::pi;

// L = a + b . w: bands 0 and 1 only, with L_00 = 4 pi a Y_0 and L_1m = (4 pi / 3) c1 b_(y, z, x).
const glm::dvec3 kA(1.0, 0.5, 2.0);
const glm::dvec3 kBx(0.3, -0.2, 0.1), kBy(0.4, 0.1, -0.5), kBz(-0.2, 0.3, 0.6);
glm::dvec3 linearRadiance(glm::dvec3 w) {
  return kA + kBx * w.x + kBy * w.y + kBz * w.z;
}
ShRgb linearSh() {
  const double c0 = 0.5 * std::sqrt(1.0 / kPi), c1 = std::sqrt(3.0 / (4.0 * kPi));
  ShRgb sh;
  sh.fill(glm::dvec3(0.0));
  sh[0] = 4.0 * kPi * c0 * kA;
  sh[1] = 4.0 * kPi / 3.0 * c1 * kBy;
  sh[2] = 4.0 * kPi / 3.0 * c1 * kBz;
  sh[3] = 4.0 * kPi / 3.0 * c1 * kBx;
  return sh;
}

double maxAbs(glm::dvec3 v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// The sum of the SH pass's texel solid angles at `level` of a `size` map.
double shSolidAngle(uint32_t size, uint32_t level) {
  const EnvMapReference ones = envMapFromFunction(size, [](glm::dvec3) { return glm::dvec3(1.0); });
  return envMapSh(ones, level)[0].x / (0.5 * std::sqrt(1.0 / kPi));
}

TEST(EnvMapReference, ConstantRadianceGivesTheConstantInEveryTexelOfEveryLevel) {
  const glm::dvec3 c(0.7, 3.25, 1e-3);
  const EnvMapReference map = envMapFromFunction(32, [&](glm::dvec3) { return c; });
  ASSERT_EQ(map.levels.size(), 6u);
  for (uint32_t level = 0; level < map.levels.size(); ++level) {
    ASSERT_EQ(map.levels[level].size(), 2u * map.levelSize(level) * map.levelSize(level));
    for (const glm::dvec3& texel : map.levels[level]) ASSERT_EQ(texel, c) << "level " << level;
  }
  // From an equirect of a constant: the bilinear weights sum to 1 to rounding.
  engine::ImageRgba32f equirect{64, 32, std::vector<float>(64 * 32 * 4, 0.5f)};
  const EnvMapReference fromImage = envMapFromEquirect(equirect, 32);
  for (const auto& level : fromImage.levels)
    for (const glm::dvec3& texel : level) ASSERT_NEAR(maxAbs(texel - glm::dvec3(0.5)), 0.0, 1e-15);
}

TEST(EnvMapReference, Level0IsTheMeanOfFourSubTexelDirectionsAndMipsAreExactMeans) {
  const uint32_t size = 16;
  const auto radiance = [](glm::dvec3 w) {
    return glm::dvec3(std::exp(2.0 * w.x), 1.0 + w.y * w.y, 3.0 + std::sin(5.0 * w.z));
  };
  const EnvMapReference map = envMapFromFunction(size, radiance);
  for (uint32_t layer = 0; layer < 2; ++layer) {
    // Texel (3, 11): the points (x + 1/4 or 3/4, y + 1/4 or 3/4) / S.
    glm::dvec3 sum(0.0);
    for (double dy : {0.25, 0.75})
      for (double dx : {0.25, 0.75})
        sum += radiance(paraboloidToDirection({(3 + dx) / size, (11 + dy) / size}, layer));
    EXPECT_LT(maxAbs(map.texel(0, layer, 3, 11) - 0.25 * sum), 1e-15);
  }
  // Level l texel = mean of the 2^l x 2^l level-0 texels under it.
  double worst = 0.0;
  for (uint32_t level = 1; level < map.levels.size(); ++level) {
    const uint32_t n = map.levelSize(level), block = size / n;
    for (uint32_t layer = 0; layer < 2; ++layer)
      for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
          glm::dvec3 mean(0.0);
          for (uint32_t j = 0; j < block; ++j)
            for (uint32_t i = 0; i < block; ++i)
              mean += map.texel(0, layer, x * block + i, y * block + j);
          mean /= double(block * block);
          worst = std::max(worst, maxAbs(map.texel(level, layer, x, y) - mean) / maxAbs(mean));
        }
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(EnvMapReference, BilinearEquirectReadWrapsInUAndClampsInV) {
  // 4 x 2 image, red = column, green = row.
  engine::ImageRgba32f image{4, 2, std::vector<float>(4 * 2 * 4, 1.0f)};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      image.pixels[(y * 4 + x) * 4 + 0] = float(x);
      image.pixels[(y * 4 + x) * 4 + 1] = float(y);
    }
  // u = 0 is halfway between the centres of columns 3 and 0; v = 0 clamps to row 0.
  EXPECT_DOUBLE_EQ(equirectBilinear(image, {0.0, 0.0}).x, 1.5);
  EXPECT_DOUBLE_EQ(equirectBilinear(image, {0.0, 0.0}).y, 0.0);
  EXPECT_DOUBLE_EQ(equirectBilinear(image, {0.999999, 1.0}).y, 1.0);
  EXPECT_DOUBLE_EQ(equirectBilinear(image, {0.375, 0.5}).x, 1.0);  // centre of column 1 ... 2
  EXPECT_DOUBLE_EQ(equirectBilinear(image, {0.375, 0.5}).y, 0.5);
  EXPECT_DOUBLE_EQ(equirectBilinear(image, {0.125, 0.25}).x, 0.0);  // texel centre (0, 0)
}

TEST(EnvMapReference, EquirectOfASmoothFunctionConvertsCloseToTheFunction) {
  // Bilinear reconstruction of a smooth function: error O(h^2), h = 2 pi / w.
  const uint32_t width = 512;
  engine::ImageRgba32f image{int(width), int(width / 2), {}};
  image.pixels.resize(size_t{width} * width / 2 * 4);
  const auto radiance = [](glm::dvec3 w) { return linearRadiance(w) + 0.5 * w * w; };
  for (uint32_t y = 0; y < width / 2; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const glm::dvec3 l =
          radiance(equirectToDirection({(x + 0.5) / width, (y + 0.5) / (width / 2)}));
      for (int c = 0; c < 3; ++c) image.pixels[(size_t{y} * width + x) * 4 + c] = float(l[c]);
      image.pixels[(size_t{y} * width + x) * 4 + 3] = 1.0f;
    }
  const EnvMapReference a = envMapFromEquirect(image, 64), b = envMapFromFunction(64, radiance);
  double worst = 0.0;
  for (size_t i = 0; i < a.levels[0].size(); ++i)
    worst = std::max(worst, maxAbs(a.levels[0][i] - b.levels[0][i]));
  std::printf("equirect %u vs function, 64^2 map: max |difference| %.2e\n", width, worst);
  EXPECT_LT(worst, 1e-3);  // (2 pi / 512)^2 ~ 1.5e-4 times second derivatives of order 1
}

TEST(EnvMapReference, ShSolidAnglesSumToFourPiWithinTheRimStaircase) {
  // Each layer weighs the 4 x 4 sub-texel points in its own hemisphere: a staircase disc of
  // (4 n)^2 cells whose area differs from the true disc's by O(perimeter) cells of alternating
  // sign (the Gauss circle problem), weighted by the rim's r = 4 b^2 per unit area. Measured:
  // +2.3e-5 relative at level 0 (256^2), -6.1e-5 at level 2 (64^2). (Counting whole texels by
  // their centres instead gave -6.1e-5 and +2.2e-3.)
  const double level0 = shSolidAngle(256, 0), level2 = shSolidAngle(256, 2);
  std::printf(
      "SH solid angle sum, S = 256: level 0 %.6f (4 pi %+.2e relative), level 2 %.6f "
      "(%+.2e)\n",
      level0, level0 / (4.0 * kPi) - 1.0, level2, level2 / (4.0 * kPi) - 1.0);
  EXPECT_NEAR(level0 / (4.0 * kPi), 1.0, 1e-4);
  EXPECT_NEAR(level2 / (4.0 * kPi), 1.0, 2e-4);
  // Both layers weigh alike (the map is symmetric); interior texels get their whole solid
  // angle, texels beyond the rim none.
  double perLayer[2] = {0.0, 0.0};
  for (uint32_t layer = 0; layer < 2; ++layer)
    for (uint32_t y = 0; y < 64; ++y)
      for (uint32_t x = 0; x < 64; ++x) perLayer[layer] += envMapTexelSolidAngle(64, layer, x, y);
  EXPECT_DOUBLE_EQ(perLayer[0], perLayer[1]);
  EXPECT_EQ(envMapTexelSolidAngle(64, 0, 0, 0), 0.0);
  const double centre = paraboloidSolidAnglePerArea(glm::dvec2(32.5 / 64, 32.5 / 64)) / 4096.0;
  EXPECT_NEAR(envMapTexelSolidAngle(64, 1, 32, 32), centre, 1e-3 * centre);  // midpoint rule
}

TEST(EnvMapReference, ShOfBandOneRadianceMatchesItsAnalyticCoefficients) {
  const EnvMapReference map = envMapFromFunction(256, linearRadiance);
  const ShRgb exact = linearSh();
  for (uint32_t level : {0u, 2u}) {
    const ShRgb sh = envMapSh(map, level);
    double worst = 0.0;
    for (int i = 0; i < kShCoefficientCount; ++i) worst = std::max(worst, maxAbs(sh[i] - exact[i]));
    std::printf("band-1 radiance, S = 256, level %u: max |L_lm - exact| %.2e (L_00 = %.3f)\n",
                level, worst, exact[0].z);
    // Measured 3.1e-4 (level 0) and 1.5e-3 (level 2) against L_00 = 7.09.
    EXPECT_LT(worst, level == 0 ? 1e-3 : 3e-3);
    // Irradiance: E(n) = pi a + (2 pi / 3) b . n exactly for this radiance.
    for (glm::dvec3 n :
         {glm::dvec3(0, 0, 1), glm::dvec3(0, -1, 0), glm::normalize(glm::dvec3(1, 1, -1))}) {
      const glm::dvec3 expected = kPi * kA + 2.0 * kPi / 3.0 * (kBx * n.x + kBy * n.y + kBz * n.z);
      EXPECT_LT(maxAbs(shIrradiance(sh, n) - expected) / maxAbs(expected), 5e-4);
    }
  }
}

TEST(EnvMapReference, RefusesSizesThatAreNotPowersOfTwo) {
  EXPECT_THROW(envMapFromFunction(48, [](glm::dvec3) { return glm::dvec3(1.0); }), engine::Error);
  EXPECT_THROW(envMapFromEquirect(engine::ImageRgba32f{}, 64), engine::Error);
}

TEST(BuiltinEnvironments, AreFiniteNonNegativeEquirectsOfHalfTheirWidth) {
  const auto names = engine::builtinEnvironmentNames();
  ASSERT_GE(names.size(), 2u);
  for (const std::string& name : names) {
    const engine::ImageRgba32f image = engine::makeBuiltinEnvironment(name, 256);
    ASSERT_EQ(image.width, 256);
    ASSERT_EQ(image.height, 128);
    ASSERT_EQ(image.pixels.size(), 256u * 128u * 4u);
    for (float v : image.pixels) {
      ASSERT_TRUE(std::isfinite(v)) << name;
      ASSERT_GE(v, 0.0f) << name;
    }
  }
}

TEST(BuiltinEnvironments, SkyHoldsTheStatedSunAndADarkerGround) {
  const uint32_t width = 1024;
  const engine::ImageRgba32f sky = engine::makeBuiltinEnvironment("sky", width);
  const glm::dvec2 uv = equirectFromDirection(glm::dvec3(engine::kSkySunDirection));
  const auto at = [&](int x, int y) {
    const float* p = &sky.pixels[(size_t(y) * width + size_t(x)) * 4];
    return glm::vec3(p[0], p[1], p[2]);
  };
  const int sx = int(uv.x * width), sy = int(uv.y * sky.height);
  EXPECT_EQ(at(sx, sy), engine::kSkySunRadiance);
  // The disc's texels: about its solid angle pi r^2 over the texel solid angles there.
  double sunSolidAngle = 0.0;
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < int(width); ++x)
      if (at(x, y) == engine::kSkySunRadiance)
        sunSolidAngle += equirectTexelSolidAngle(uint32_t(y), width, uint32_t(sky.height));
  const double disc = 2.0 * kPi * (1.0 - std::cos(double(engine::kSkySunAngularRadius)));
  std::printf("sun disc: %.3e sr of texels, %.3e sr exact\n", sunSolidAngle, disc);
  EXPECT_NEAR(sunSolidAngle / disc, 1.0, 0.05);
  // Ground below the horizon, darker than the sky just above it.
  EXPECT_EQ(at(10, sky.height - 1), engine::kSkyGround);
  EXPECT_LT(at(10, sky.height / 2).y, at(10, sky.height / 2 - 1).y);
}

TEST(BuiltinEnvironments, StudioHasBrightLightsAndAHighFrequencyBand) {
  const engine::ImageRgba32f studio = engine::makeBuiltinEnvironment("studio", 1024);
  float brightest = 0.0f;
  for (float v : studio.pixels) brightest = std::max(brightest, v);
  EXPECT_GE(brightest, 40.0f);
  // Along the row just above the horizon the checker alternates every 8 texels (128 cells).
  const int row = studio.height / 2 - 1;
  int changes = 0;
  for (int x = 1; x < studio.width; ++x)
    changes += studio.pixels[(size_t(row) * 1024 + x) * 4] !=
               studio.pixels[(size_t(row) * 1024 + x - 1) * 4];
  EXPECT_EQ(changes, 127);
}

TEST(BuiltinEnvironments, RefuseUnknownNamesListingTheKnownOnesAndBadWidths) {
  try {
    engine::makeBuiltinEnvironment("moon");
    FAIL() << "no error";
  } catch (const engine::Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'moon'"), std::string::npos) << message;
    for (const std::string& name : engine::builtinEnvironmentNames())
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
  EXPECT_THROW(engine::makeBuiltinEnvironment("sky", 7), engine::Error);
  EXPECT_THROW(engine::makeBuiltinEnvironment("sky", 2), engine::Error);
}

}  // namespace
}  // namespace gi
