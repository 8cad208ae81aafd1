// The accuracy gate (docs/accuracy.md): the module's indirect light, through the public API at
// its default settings, against the path tracer's on every built-in scene. The references are
// traced here (cached in the build tree, keyed by everything that changes them) at the size the
// bounds were measured at. Bounds: the measured values with the margins stated beside them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "engine/builtin_scenes.h"
#include "engine/image_metrics.h"
#include "gi_host.h"
#include "gpu_fixture.h"
#include "light_rigs.h"
#include "path_tracer.h"
#include "reference_cache.h"
#include "room_shell.h"

namespace {

constexpr uint32_t kWidth = 160, kHeight = 90;

// Per scene, measured at 160 x 90 with the module's defaults (RSM 256^2, BRSM PDF, modified FIS,
// K = 1, kernels kept on their surfaces, ISMs, adaptive shading) against a 3 % path-traced
// reference (docs/accuracy.md has the run). The reference and the module are deterministic, so the
// margins only absorb other devices' fp32 rounding and small legitimate changes: relMSE bounds are
// the measured N = 512 value + 15 %; the mean may stray from the path tracer's by the measured
// amount + 3 % of it; relMSE must fall from N = 64 to 512 by the measured ratio + 0.1 (the issue's
// target is 0.6).
struct Bounds {
  const char* scene;
  double relativeMse512;  // measured 0.00429, 0.00281, 0.00358, 0.00507
  double meanError512;    // |mean ratio - 1|: measured 0.021, 0.028, 0.080, 0.078
  double convergence;     // relMSE(512) / relMSE(64): measured 0.40, 0.35, 0.59, 0.40
  bool leakFails;         // the planar leak (planarEmitters off) must exceed the relMSE bound
};
constexpr Bounds kBounds[] = {
    {"cornell", 0.0049, 0.051, 0.50, true},
    {"atrium", 0.0032, 0.058, 0.45, true},
    {"checker", 0.0041, 0.110, 0.69, false},  // little planar leak: 0.00436 off
    // Four lights of all three types: 1.42x the three one-light scenes' mean relMSE (the
    // many-lights target is 1.5x); planar emitters off measures 0.00578.
    {"lounge", 0.0058, 0.108, 0.50, false},
};

struct Score {
  double relativeMse = 0.0;
  double meanRatio = 0.0;  // module mean / path-tracer mean (RGB averaged)
};

// A scene, its G-buffer and its path-traced reference; score() renders the module's frame.
class AccuracyTest : public testing_gpu::GpuTest {
 protected:
  void prepare(engine::Scene scene) {
    scene_ = std::move(scene);
    view_ = engine::cameraView(scene_.cameras.at(0), kWidth, kHeight);
    gpuScene_ = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx(), scene_));
    gbuffer_ = std::make_unique<engine::GBuffer>(renderGBuffer(*gpuScene_, view_));
    // Every light of the scene bounces, in the module and in the path tracer.
    ASSERT_FALSE(scene_.lights.empty());
    std::vector<uint32_t> lights(scene_.lights.size());
    for (uint32_t i = 0; i < lights.size(); ++i) lights[i] = i;
    truth::PathTraceSettings settings;
    settings.relativeError = 0.03;  // the benchmark's references' target
    const truth::ReferenceCache cache(VSGL_TEST_CACHE);
    const truth::PathTraceImage traced =
        truth::cachedPathTrace(cache, scene_, view_, lights, settings);
    reference_.resize(traced.diffuse.size());
    for (size_t i = 0; i < reference_.size(); ++i)
      reference_[i] = traced.diffuse[i] + traced.glossy[i];
  }

  Score score(const gi::Settings& settings, gi::FramePlan* plan = nullptr) {
    std::unique_ptr<gi::IndirectLighting> lighting =
        samples::createIndirect(ctx(), settings, kWidth, kHeight, *gpuScene_, scene_);
    gi::FrameOutput out;
    const gi::FrameInput in = samples::frameInput(*gbuffer_, view_, scene_.lights);
    ctx().submitAndWait(
        [&](VkCommandBuffer cmd) { samples::check(lighting->record(cmd, in, &out)); });
    if (plan) *plan = lighting->lastPlan();
    for (engine::Image* image :
         {&gbuffer_->depth, &gbuffer_->normal, &gbuffer_->diffuse, &gbuffer_->specular})
      image->setLayout(out.gbufferLayout);
    const std::vector<glm::dvec3> test =
        samples::indirectSum(samples::readIndirect(ctx(), out, kWidth, kHeight));
    const engine::ErrorMetrics m = engine::compareImages(test, reference_);
    double mean = 0.0;
    for (const glm::dvec3& c : test) mean += (c.r + c.g + c.b) / 3.0;
    mean /= double(test.size());
    return {m.relativeMse, mean / m.referenceMean};
  }

  // The defaults at N = 64 and 512 against the path tracer, printed as `what`, held to the
  // bounds: relMSE at 512, |mean ratio - 1| at 512, relMSE(512) / relMSE(64).
  void expectDefaultsWithin(const char* what, double relativeMse512, double meanError512,
                            double convergence) {
    gi::Settings settings;
    settings.vsglCount = 64;
    const Score few = score(settings);
    settings.vsglCount = 512;
    const Score many = score(settings);
    std::printf("%s: relMSE %.5f (N = 64), %.5f (N = 512); mean ratio %.4f, %.4f\n", what,
                few.relativeMse, many.relativeMse, few.meanRatio, many.meanRatio);
    EXPECT_LE(many.relativeMse, relativeMse512);
    EXPECT_LE(std::abs(many.meanRatio - 1.0), meanError512);
    EXPECT_LE(many.relativeMse, convergence * few.relativeMse) << "more VSGLs must buy accuracy";
  }

  engine::Scene scene_;
  engine::View view_;
  std::unique_ptr<engine::SceneGpu> gpuScene_;
  std::unique_ptr<engine::GBuffer> gbuffer_;
  std::vector<glm::dvec3> reference_;
};

class AccuracyGate : public AccuracyTest, public ::testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    AccuracyTest::SetUp();
    if (IsSkipped()) return;
    prepare(engine::makeBuiltinScene(GetParam()));
  }
};

TEST_P(AccuracyGate, IndirectLightAgainstPathTracer) {
  gi::Settings settings;  // the module's defaults, as a host gets them
  settings.vsglCount = 64;
  const Score few = score(settings);
  settings.vsglCount = 512;
  const Score many = score(settings);
  settings.planarEmitters = false;
  const Score leaky = score(settings);
  std::printf(
      "%s: relMSE %.5f (N = 64), %.5f (N = 512), %.5f (N = 512, planar emitters off); "
      "mean ratio %.4f, %.4f, %.4f\n",
      GetParam().c_str(), few.relativeMse, many.relativeMse, leaky.relativeMse, few.meanRatio,
      many.meanRatio, leaky.meanRatio);
  const Bounds* b = nullptr;
  for (const Bounds& candidate : kBounds)
    if (GetParam() == candidate.scene) b = &candidate;
  ASSERT_NE(b, nullptr);
  EXPECT_LE(many.relativeMse, b->relativeMse512);
  EXPECT_LE(std::abs(many.meanRatio - 1.0), b->meanError512);
  EXPECT_LE(many.relativeMse, b->convergence * few.relativeMse) << "more VSGLs must buy accuracy";
  if (b->leakFails) {
    EXPECT_GT(leaky.relativeMse, b->relativeMse512) << "the gate must catch the planar leak";
  }
}

// The VPL baseline (docs/techniques/vpl-baseline.md), what the benchmark compares the module
// with, held to its own measured accuracy with the margins above: relMSE at N = 512 (measured
// 0.00546, 0.00171, 0.00797, 0.00490), its mean (|ratio - 1| measured 0.007, 0.001, 0.054,
// 0.038) and its convergence from N = 64 (measured 0.57, 0.46, 0.70, 0.37). A baseline that
// silently lost accuracy would make the module look better than it is.
struct VplBounds {
  const char* scene;
  double relativeMse512, meanError512, convergence;
};
constexpr VplBounds kVplBounds[] = {
    {"cornell", 0.0063, 0.039, 0.67},
    {"atrium", 0.0020, 0.031, 0.56},
    {"checker", 0.0092, 0.084, 0.80},
    {"lounge", 0.0056, 0.068, 0.47},
};

TEST_P(AccuracyGate, VplBaselineAgainstPathTracer) {
  gi::Settings settings;
  settings.method = gi::VsglMethod::Vpl;
  settings.vsglCount = 64;
  const Score few = score(settings);
  settings.vsglCount = 512;
  const Score many = score(settings);
  std::printf("%s, VPL baseline: relMSE %.5f (N = 64), %.5f (N = 512); mean ratio %.4f, %.4f\n",
              GetParam().c_str(), few.relativeMse, many.relativeMse, few.meanRatio, many.meanRatio);
  const VplBounds* b = nullptr;
  for (const VplBounds& candidate : kVplBounds)
    if (GetParam() == candidate.scene) b = &candidate;
  ASSERT_NE(b, nullptr);
  EXPECT_LE(many.relativeMse, b->relativeMse512);
  EXPECT_LE(std::abs(many.meanRatio - 1.0), b->meanError512);
  EXPECT_LE(many.relativeMse, b->convergence * few.relativeMse);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, AccuracyGate,
                         ::testing::Values("cornell", "atrium", "checker", "lounge"));

// A planner decision that leaves a pass out must not cost more accuracy than it saves. The
// planner skips the ISMs when nothing can occlude (SceneGeometry::canOcclude = false: the
// inside of a convex room), removing their own errors. The hard case is an open-top room under
// a low sun: the sun lights the outer face of one wall, whose light the wall itself keeps out of
// the room, and without ISMs only the light model (planar emitters, a flat cluster sends
// nothing behind its plane) keeps it out. The Cornell box's walls and floor without the ceiling
// and the boxes (testing_gpu::roomShell), a sun from above the right wall (+x) at 40 degrees from
// the vertical. The walls are double-sided here: a single-sided wall's outer face reflects nothing
// in the light's view (engine::BackFaces), which would take the hard case away. Measured at
// N = 512: relMSE 0.0032 with the ISMs skipped, 0.0036 with them (means 0.962, 0.950); with
// planar emitters off (checked by hand) 0.036 against 0.022, which fails.
TEST_F(AccuracyTest, SkippingTheIsmsInAnOpenRoomSavesMoreErrorThanItCosts) {
  const engine::Scene cornell = engine::makeBuiltinScene("cornell");
  engine::Scene room = testing_gpu::roomShell(cornell, true);
  engine::Light sun;
  sun.name = "sun";
  sun.type = engine::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-std::sin(0.7f), -std::cos(0.7f), 0.0f));
  sun.intensity = 3.0f;
  room.lights = {sun};
  for (engine::Material& m : room.materials) m.doubleSided = true;
  ASSERT_LT(room.triangleCount(), cornell.triangleCount());
  ASSERT_FALSE(samples::canOcclude(room)) << "the open room must be convex for the planner";
  prepare(room);

  gi::Settings settings;  // the defaults, at the gate's larger count
  settings.vsglCount = 512;
  gi::FramePlan skipped, kept;
  const Score skip = score(settings, &skipped);
  settings.planner.skipWithoutOccluders = false;
  const Score ism = score(settings, &kept);
  std::printf(
      "open room under the sun: relMSE %.5f with the ISMs skipped, %.5f with them; mean ratio "
      "%.4f, %.4f\n",
      skip.relativeMse, ism.relativeMse, skip.meanRatio, ism.meanRatio);
  EXPECT_FALSE(skipped.visibility);
  EXPECT_TRUE(kept.visibility);
  EXPECT_LE(skip.relativeMse, ism.relativeMse);
  EXPECT_LE(std::abs(skip.meanRatio - 1.0), std::abs(ism.meanRatio - 1.0));
}

// A point light (docs/techniques/point-lights.md) where the Cornell box's spot hangs, 0.1 m
// under the ceiling, at a quarter of its intensity. It lights every surface of the room and every
// corner from both sides, the near field at contact lines that the VSGL model handles worst
// (docs/accuracy.md), so it falls short of the target of the spot's relMSE x 1.2:
// measured relMSE 0.0282 (N = 64), 0.0120 (N = 512) against the spot's 0.0043, mean ratio 0.926.
// Bounds with the gate's margins: relMSE + 15 %, |mean - 1| + 0.03, convergence + 0.1.
TEST_F(AccuracyTest, PointLightAgainstPathTracer) {
  engine::Scene cornell = engine::makeBuiltinScene("cornell");
  engine::Light& light = cornell.lights.at(0);
  light.type = engine::LightType::Point;
  light.intensity *= 0.25f;
  prepare(cornell);
  expectDefaultsWithin("cornell, point light", 0.0138, 0.104, 0.52);
}

// Lights of all three kinds at once (docs/techniques/many-lights.md): the Cornell box's spot, a
// point light in the middle of the room at a quarter of its intensity, and a sun through the
// open front, against the path tracer bouncing all three. Measured: relMSE 0.0579 (N = 64),
// 0.0217 (N = 512), mean ratio 0.816, 0.909 (5.0x the Cornell box's spot alone, where the
// lounge of the gate is 1.42x the one-light scenes): the point light's contact lines
// (PointLightAgainstPathTracer) and the sun's small lit patch inside the box, seen through its
// open front, are the error. Bounds with the gate's margins.
TEST_F(AccuracyTest, ThreeLightsAgainstPathTracer) {
  engine::Scene cornell = engine::makeBuiltinScene("cornell");
  const engine::Light point = testing_gpu::middlePointLight(cornell);
  engine::Light sun;
  sun.name = "sun";
  sun.type = engine::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -0.5f, -1.0f));
  sun.intensity = 1.0f;
  cornell.lights.push_back(point);
  cornell.lights.push_back(sun);
  prepare(cornell);
  expectDefaultsWithin("cornell, three lights", 0.0249, 0.121, 0.47);
}

}  // namespace
