// The environment conversion on the GPU (gi/src/passes/env_map.h) against its CPU twin
// (gi/src/reference/env_map_reference.h): every texel of every level, the SH projection, SH
// irradiance against analytic values, and the refusal of bad input.
//
// Tolerance of a converted texel. The GPU evaluates in fp32 what the twin evaluates in double:
// direction (about 10 operations), atan2 (the shader's own, exact to rounding), the bilinear
// read (8 operations) and the 4-point mean. Two kinds of error follow.
//   (1) Arithmetic on the values: about 10 roundings, |error| <= 10 u M with u = 2^-24 and M the
//       largest radiance the texel reads: 6e-7 M.
//   (2) The read position: (u, v) carries a few ulp of error, i.e. about 3e-7 x 1024 = 3e-4
//       texels of the equirect image (more next to the poles, where u is ill-conditioned, but
//       there every image here is smooth in u), and a bilinear read moved by d texels changes
//       by at most 2 d G, G the largest difference between neighbouring texels.
// M and G of a map texel are bounded by converting, with the twin, the images of the 3 x 3 local
// maximum of |L| and the 3 x 3 local maximum of |L(neighbour) - L| (both bilinear reads are
// convex combinations, so this bounds what the texel read). The test allows
//   |gpu - twin| <= 2e-6 M + 1e-3 G (+ 2 l u M at mip level l, shared/mip_reduce.h),
// about 3x the estimates above, and prints the largest fraction of it used (lavapipe: 0.09 for
// sky and studio, whose sun and checker edges make the position term dominate; worst
// |gpu - twin| / M 1.1e-5 and 4.5e-5 there, 4e-7 for a smooth environment).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "engine/commands.h"
#include "engine/environments.h"
#include "gpu_fixture.h"
#include "passes/env_map.h"
#include "reference/env_map_reference.h"
#include "reference/env_paraboloid.h"
#include "reference/sh_irradiance.h"
#include "shared/environment.h"
#include "test_environments.h"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kU = 0x1p-24;
using testing_common::equirectOf;

// The 3 x 3 neighbourhood statistics of an equirect (u wraps, v clamps), as images: the local
// maximum of |L| (difference = false) or of |L(neighbour) - L| (difference = true).
engine::ImageRgba32f localBound(const engine::ImageRgba32f& image, bool difference) {
  engine::ImageRgba32f out = image;
  const int w = image.width, h = image.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const float centre = image.pixels[(size_t(y) * w + x) * 4 + c];
        float bound = 0.0f;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = (x + dx + w) % w, ny = std::clamp(y + dy, 0, h - 1);
            const float v = image.pixels[(size_t(ny) * w + nx) * 4 + c];
            bound = std::max(bound, difference ? std::abs(v - centre) : std::abs(v));
          }
        out.pixels[(size_t(y) * w + x) * 4 + c] = bound;
      }
  return out;
}

double maxAbs(glm::dvec3 v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

gi::ShRgb toShRgb(const gpu::EnvSh& sh) {
  gi::ShRgb out;
  for (int i = 0; i < gi::kShCoefficientCount; ++i) out[i] = glm::dvec3(sh.coefficients[i]);
  return out;
}

class EnvMapTest : public testing_gpu::GpuTest {
 protected:
  struct Converted {
    std::vector<std::vector<glm::vec4>> levels;  // [level][(layer n + y) n + x]
    gpu::EnvSh sh{};
    uint32_t shLevel = 0;
  };

  Converted convert(const engine::ImageRgba32f& equirect, uint32_t size) {
    gi::EnvironmentMap env(ctx(), size);
    env.upload(ctx(), equirect);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      env.record(cmd);
      engine::computeToTransferBarrier(cmd);
    });
    Converted out;
    EXPECT_EQ(env.levels(), uint32_t(std::bit_width(size)));
    for (uint32_t level = 0; level < env.levels(); ++level)
      out.levels.push_back(env.map().readbackRgba32f(ctx(), level));
    out.sh = env.sh().readbackAs<gpu::EnvSh>(ctx()).at(0);
    out.shLevel = env.shLevel();
    return out;
  }

  // Every texel of every level against the twin, within the bound of the file comment.
  void compareWithTwin(const std::string& what, const engine::ImageRgba32f& equirect,
                       uint32_t size) {
    const Converted gpu = convert(equirect, size);
    const gi::EnvMapReference twin = gi::envMapFromEquirect(equirect, size);
    const gi::EnvMapReference magnitude = gi::envMapFromEquirect(localBound(equirect, false), size);
    const gi::EnvMapReference gradient = gi::envMapFromEquirect(localBound(equirect, true), size);
    ASSERT_EQ(gpu.levels.size(), twin.levels.size());
    double worstFraction = 0.0, worstRelative = 0.0;
    for (uint32_t level = 0; level < twin.levels.size(); ++level) {
      ASSERT_EQ(gpu.levels[level].size(), twin.levels[level].size());
      for (size_t i = 0; i < twin.levels[level].size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const double m = magnitude.levels[level][i][c], g = gradient.levels[level][i][c];
          const double bound = (2e-6 + 2.0 * level * kU) * m + 1e-3 * g;
          const double error = std::abs(double(gpu.levels[level][i][c]) - twin.levels[level][i][c]);
          worstFraction = std::max(worstFraction, error / bound);
          if (m > 0.0) worstRelative = std::max(worstRelative, error / m);
          ASSERT_LE(error, bound) << what << ": level " << level << " texel " << i << " channel "
                                  << c << " gpu " << gpu.levels[level][i][c] << " twin "
                                  << twin.levels[level][i][c] << " M " << m << " G " << g;
        }
    }
    std::printf("%s, S = %u: worst |gpu - twin| / M %.2e, %.2f of the bound\n", what.c_str(), size,
                worstRelative, worstFraction);

    // The SH pass against the twin's projection of the GPU's own level (this isolates the SH
    // pass): fp32 sums of 64 terms per thread and a 7-step tree, plus about 22 roundings per
    // term (16 of them in the texel's solid angle), give |error| <= 93 u sum w |L| |Y| with
    // |Y| <= 1.1, i.e. 6e-6 sum w |L|; allowed 1e-5 (measured on lavapipe: below 1e-7).
    gi::EnvMapReference level;
    level.size = size >> gpu.shLevel;
    level.levels.resize(1);
    gi::EnvMapReference absolute = level;
    for (const glm::vec4& texel : gpu.levels[gpu.shLevel]) {
      level.levels[0].push_back(glm::dvec3(texel));
      absolute.levels[0].push_back(glm::abs(glm::dvec3(texel)));
    }
    const gi::ShRgb expected = gi::envMapSh(level, 0);
    const glm::dvec3 scale = gi::envMapSh(absolute, 0)[0] / (0.5 * std::sqrt(1.0 / kPi));
    const gi::ShRgb sh = toShRgb(gpu.sh);
    double worstSh = 0.0;
    for (int i = 0; i < gi::kShCoefficientCount; ++i)
      for (int c = 0; c < 3; ++c) {
        const double error = std::abs(sh[i][c] - expected[i][c]);
        worstSh = std::max(worstSh, error / scale[c]);
        EXPECT_LE(error, 1e-5 * scale[c]) << what << ": SH " << i << " channel " << c;
      }
    std::printf("%s: SH at level %u (%u^2), worst |gpu - twin| / sum w|L| %.2e\n", what.c_str(),
                gpu.shLevel, size >> gpu.shLevel, worstSh);
  }
};

TEST_F(EnvMapTest, SkyConvertsLikeTheTwinAtEveryLevel) {
  compareWithTwin("sky 1024", engine::makeBuiltinEnvironment("sky", 1024), 256);
}

TEST_F(EnvMapTest, StudioConvertsLikeTheTwinAtEveryLevel) {
  compareWithTwin("studio 1024", engine::makeBuiltinEnvironment("studio", 1024), 256);
}

TEST_F(EnvMapTest, SmoothEnvironmentConvertsLikeTheTwinAtEveryLevel) {
  const auto smooth = [](glm::dvec3 w) {
    return glm::dvec3(1.0 + 0.5 * w.x * w.z, 2.0 + std::sin(3.0 * w.y), std::exp(w.x + w.z));
  };
  compareWithTwin("smooth 512", equirectOf(512, smooth), 128);
  compareWithTwin("smooth 256 to a 32 map", equirectOf(256, smooth), 32);
}

// Irradiance from the GPU's SH of analytic radiance. The quadrature error of the projection is
// the SH pass's rim staircase (weights sum to 4 pi within 2e-3 at 64^2,
// tests/unit/test_env_map_reference.cpp) plus the bilinear reconstruction and the band-2
// leakage of the staircase: allowed 1e-3 of the largest |E| component (measured on lavapipe:
// 1.5e-4 for white, 2.0e-4 for the linear gradient).
TEST_F(EnvMapTest, ShIrradianceOfConstantAndLinearRadianceMatchesTheAnalyticValue) {
  const glm::dvec3 a(1.0, 0.5, 2.0), bx(0.3, -0.2, 0.1), by(0.4, 0.1, -0.5), bz(-0.2, 0.3, 0.6);
  const Converted white = convert(engine::makeBuiltinEnvironment("white", 512), 256);
  const Converted linear = convert(
      equirectOf(1024, [&](glm::dvec3 w) { return a + bx * w.x + by * w.y + bz * w.z; }), 256);
  double worstWhite = 0.0, worstLinear = 0.0;
  for (int i = 0; i < 26; ++i) {
    const glm::dvec3 n = gi::equirectToDirection({(i % 7 + 0.3) / 7.0, (i / 7 + 0.5) / 4.0});
    const glm::dvec3 e = gi::shIrradiance(toShRgb(white.sh), n);
    worstWhite = std::max(worstWhite, maxAbs(e - glm::dvec3(kPi)) / kPi);
    const glm::dvec3 exact = kPi * a + 2.0 * kPi / 3.0 * (bx * n.x + by * n.y + bz * n.z);
    worstLinear = std::max(worstLinear,
                           maxAbs(gi::shIrradiance(toShRgb(linear.sh), n) - exact) / maxAbs(exact));
  }
  std::printf("SH irradiance, relative error: white %.2e, linear %.2e\n", worstWhite, worstLinear);
  EXPECT_LT(worstWhite, 1e-3);
  EXPECT_LT(worstLinear, 1e-3);
}

TEST_F(EnvMapTest, ConstantEnvironmentGivesTheConstantAtEveryLevel) {
  const Converted white = convert(engine::makeBuiltinEnvironment("white", 64), 16);
  // Bilinear weights (1 - f) + f = 1 up to one rounding each; box means of equal values exact.
  for (const auto& level : white.levels)
    for (const glm::vec4& texel : level)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(texel[c], 1.0f, 4.0 * kU);
}

TEST_F(EnvMapTest, RefusesBadImagesAndSizes) {
  gi::EnvironmentMap env(ctx(), 16);
  const auto expectError = [&](engine::ImageRgba32f image, const std::string& words) {
    try {
      env.upload(ctx(), image);
      ADD_FAILURE() << "no error for " << words;
    } catch (const engine::Error& error) {
      EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
  };
  expectError(engine::ImageRgba32f{}, "empty");
  expectError(engine::ImageRgba32f{8, 4, std::vector<float>(10, 1.0f)}, "expected 128");
  engine::ImageRgba32f image = engine::makeBuiltinEnvironment("white", 8);
  image.pixels[(2 * 8 + 5) * 4 + 1] = std::nanf("");
  expectError(image, "pixel (5, 2) channel g is NaN");
  image.pixels[(2 * 8 + 5) * 4 + 1] = INFINITY;
  expectError(image, "infinite");
  image.pixels[(2 * 8 + 5) * 4 + 1] = -1.0f;
  expectError(image, "negative");
  image.pixels[(2 * 8 + 5) * 4 + 1] = 1.0f;
  image.pixels[(2 * 8 + 5) * 4 + 3] = -1.0f;  // alpha is ignored
  EXPECT_NO_THROW(env.upload(ctx(), image));

  EXPECT_THROW(gi::EnvironmentMap(ctx(), 48), engine::Error);
  EXPECT_THROW(gi::EnvironmentMap(ctx(), 0), engine::Error);
  gi::EnvironmentMap empty(ctx(), 16);
  EXPECT_THROW(ctx().submitAndWait([&](VkCommandBuffer cmd) { empty.record(cmd); }), engine::Error);
}

}  // namespace
