// The path tracer against the analytic scene's quadrature (gi/truth/analytic_scene.h): the
// wall's one-bounce radiance and the floor's direct light, plus determinism across thread
// counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analytic_scene.h"
#include "embree_scene.h"
#include "engine/gbuffer_reference.h"
#include "path_tracer.h"
#include "reference/rsm_reference.h"

namespace {

constexpr uint32_t kWidth = 40, kHeight = 24;  // aspect 1.66: the wall spans the width

struct Fixture {
  truth::AnalyticSceneParams params;
  engine::Scene scene = truth::makeAnalyticScene(params);
  truth::EmbreeScene rays{scene};
  engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
};

// Each wall pixel's estimate against the quadrature. Tolerances: the 1 % on the summed
// wall radiance, and that sum within 4 of its standard errors (the per-pixel ones combined:
// pixels are independent); per pixel, at most 1 % of the pixels beyond 4.5 standard errors
// (4.5 sigma is rare for a Gaussian, and the estimator's heavier tail is bounded by the noise
// target).
TEST(PathTracer, MatchesAnalyticOneBounce) {
  Fixture f;
  truth::PathTraceSettings s;
  s.relativeError = 0.005;
  const truth::PathTraceImage image = truth::pathTrace(f.scene, f.rays, f.view, 0, s);
  double traced = 0.0, exact = 0.0, variance = 0.0, tracedGlossy = 0.0, exactGlossy = 0.0;
  int pixels = 0, outliers = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const engine::CameraRay ray =
          engine::cameraRayReference(f.view, glm::dvec2(x + 0.5, y + 0.5));
      const std::optional<glm::dvec3> wall = truth::analyticWallHit(f.params, ray.origin, ray.dir);
      if (!wall) continue;
      const glm::dvec3 p = *wall, toEye = -ray.dir;
      const size_t i = size_t{y} * kWidth + x;
      const truth::OneBounceRadiance oracle = truth::analyticOneBounce(f.params, p, toEye);
      const double t = gi::luminance709(image.diffuse[i] + image.glossy[i]);
      const double e = gi::luminance709(oracle.diffuse + oracle.glossy);
      traced += t;
      exact += e;
      tracedGlossy += gi::luminance709(image.glossy[i]);
      exactGlossy += gi::luminance709(oracle.glossy);
      variance += image.standardError[i] * image.standardError[i];
      if (std::abs(t - e) > 4.5 * image.standardError[i]) ++outliers;
      ++pixels;
      EXPECT_EQ(image.direct[i], glm::dvec3(0.0)) << "the wall gets no direct light";
    }
  ASSERT_GT(pixels, int(kWidth * kHeight) / 2);
  const double error = std::abs(traced - exact) / exact;
  std::printf(
      "%d wall pixels: traced %.6g, quadrature %.6g, error %.3g %% (%.2f standard "
      "errors); glossy %.6g vs %.6g; %d pixels beyond 4.5 sigma; %.1f s\n",
      pixels, traced, exact, 100.0 * error, std::abs(traced - exact) / std::sqrt(variance),
      tracedGlossy, exactGlossy, outliers, image.seconds);
  EXPECT_LT(error, 0.01);
  EXPECT_LT(std::abs(traced - exact), 4.0 * std::sqrt(variance));
  EXPECT_LE(outliers, pixels / 100);
}

// Direct light is deterministic (point light, exact shadow ray): the floor pixels equal the
// closed form up to Embree's fp32 hit points (relative 1e-5 covers a few fp32 ulps of position
// amplified by the 1/d^3 falloff).
TEST(PathTracer, DirectLightMatchesClosedForm) {
  Fixture f;
  truth::PathTraceSettings s;
  s.minSamples = 2;
  s.maxSamples = 2;
  const truth::PathTraceImage image = truth::pathTrace(f.scene, f.rays, f.view, 0, s);
  int lit = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const engine::CameraRay ray =
          engine::cameraRayReference(f.view, glm::dvec2(x + 0.5, y + 0.5));
      if (ray.dir.y >= 0.0) continue;
      const glm::dvec3 p = ray.origin + (-ray.origin.y / ray.dir.y) * ray.dir;
      if (p.x >= f.params.wallX - 0.01) continue;  // behind or at the wall
      const glm::dvec3 expected = truth::analyticFloorDirectRadiance(f.params, p, -ray.dir);
      const glm::dvec3 got = image.direct[size_t{y} * kWidth + x];
      if (expected.x > 0.0) ++lit;
      EXPECT_NEAR(got.x, expected.x, 1e-5 * expected.x + 1e-12) << x << ", " << y;
    }
  EXPECT_GT(lit, 0);
}

// One stream per pixel: the image does not depend on how pixels are spread over threads.
TEST(PathTracer, SameImageOnAnyThreadCount) {
  Fixture f;
  truth::PathTraceSettings s;
  s.relativeError = 0.05;
  s.maxSamples = 512;
  s.threads = 1;
  const truth::PathTraceImage one = truth::pathTrace(f.scene, f.rays, f.view, 0, s);
  s.threads = 3;
  const truth::PathTraceImage three = truth::pathTrace(f.scene, f.rays, f.view, 0, s);
  EXPECT_EQ(one.diffuse, three.diffuse);
  EXPECT_EQ(one.glossy, three.glossy);
  EXPECT_EQ(one.samples, three.samples);
}

}  // namespace
