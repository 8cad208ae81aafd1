// The error budget's CPU stages (gi/truth/error_budget.h): kernel weights that tile exactly
// read 1 (each kernel in its own RSM view), the numeric SG stage agrees with the analytic twin
// where that twin is accurate, area visibility is what a kernel's own VPLs see, the flat share is
// the flat VSGLs' light, and the regions find the floor under a lit floor and the floor-wall
// lines.
#include <gtest/gtest.h>

#include <cstdio>

#include "embree_scene.h"
#include "engine/builtin_scenes.h"
#include "error_budget.h"
#include "test_vsgls.h"

namespace {

constexpr uint32_t kRsm = 16;

// Every texel a VPL of diffuse reflected power 0.5 (luminance), no specular lobe.
std::vector<truth::Vpl> uniformVpls() {
  std::vector<truth::Vpl> vpls(kRsm * kRsm);
  for (uint32_t t = 0; t < vpls.size(); ++t) {
    truth::Vpl& v = vpls[t];
    v.normal = v.geometricNormal = v.toLight = {0.0, 1.0, 0.0};
    v.incident = glm::dvec3(1.0);
    v.diffuse = glm::dvec3(0.5);
    v.f0 = glm::dvec3(0.0);
    v.f90 = 0.0;
    v.roughness = 0.5;
    v.texel = t;
  }
  return vpls;
}

// A filtered-sampling record whose kernel is centred at x with level l and whose lobes carry
// `power` (luminance), as generation would scale them.
gpu::Vsgl kernelVsgl(glm::vec2 x, float level, float power) {
  gpu::Vsgl v{};
  v.diffuse = testing_gpu::vsglLobe({0, 0, 0}, 0.0f, {0, 1, 0}, 2.29f, glm::vec3(power));
  v.kernel = glm::vec4(x, level, 1.0f);
  return v;
}

}  // namespace

// Four level-3 kernels (a 16^2 map: each level-3 texel is one quadrant), each with its
// quadrant's power: a perfect tiling, weight 1 on every texel. Without one of them its quadrant
// reads 0 (a gap); the same four twice, at half the power each, still read 1 (overlaps that
// share the power are not double counting).
TEST(ErrorBudget, KernelWeightsReadTheTiling) {
  const std::vector<truth::Vpl> vpls = uniformVpls();
  const float quadrant = 0.5f * kRsm * kRsm / 4.0f;
  std::vector<gpu::Vsgl> vsgls;
  for (glm::vec2 c : {glm::vec2(0.25f, 0.25f), glm::vec2(0.75f, 0.25f), glm::vec2(0.25f, 0.75f),
                      glm::vec2(0.75f, 0.75f)})
    vsgls.push_back(kernelVsgl(c, 3.0f, quadrant));
  for (double w : truth::kernelTexelWeights(vsgls, {kRsm}, vpls)) EXPECT_NEAR(w, 1.0, 1e-12);

  std::vector<gpu::Vsgl> gap(vsgls.begin(), vsgls.begin() + 3);
  const std::vector<double> gapWeights = truth::kernelTexelWeights(gap, {kRsm}, vpls);
  for (uint32_t y = 0; y < kRsm; ++y)
    for (uint32_t x = 0; x < kRsm; ++x)
      EXPECT_NEAR(gapWeights[y * kRsm + x], x >= kRsm / 2 && y >= kRsm / 2 ? 0.0 : 1.0, 1e-12);

  std::vector<gpu::Vsgl> twice;
  for (gpu::Vsgl v : vsgls) {
    v.diffuse.power *= 0.5f;
    twice.push_back(v);
    twice.push_back(v);
  }
  for (double w : truth::kernelTexelWeights(twice, {kRsm}, vpls)) EXPECT_NEAR(w, 1.0, 1e-6);

  // A kernel between levels and texels spreads over its trilinear footprint; its weights carry
  // exactly its power.
  const gpu::Vsgl blurred = kernelVsgl({0.4f, 0.55f}, 1.6f, 3.0f);
  const std::vector<double> spread = truth::kernelTexelWeights({blurred}, {kRsm}, vpls);
  double carried = 0.0;
  size_t touched = 0;
  for (double w : spread) {
    carried += 0.5 * w;
    touched += w > 0.0;
  }
  EXPECT_NEAR(carried, 3.0, 1e-9);
  EXPECT_GT(touched, 16u);

  // k-means clusters partition the texels.
  gpu::Vsgl cluster = blurred;
  cluster.kernel = glm::vec4(0.0f, 0.0f, -1.0f, 12.0f);
  for (double w : truth::kernelTexelWeights({cluster}, {kRsm}, vpls)) EXPECT_EQ(w, 1.0);
}

// Kernels of several RSM views (a point light's cube faces, several lights): a kernel of view v
// weighs the texels from v * rsmSize^2, as rsmVpls numbers the VPLs. Two views of uniform VPLs,
// the four quadrant kernels in view 1 only: view 1 reads 1, view 0 nothing.
TEST(ErrorBudget, KernelWeightsFollowTheirView) {
  std::vector<truth::Vpl> vpls = uniformVpls();
  for (truth::Vpl v : uniformVpls()) {
    v.texel += kRsm * kRsm;
    vpls.push_back(v);
  }
  const float quadrant = 0.5f * kRsm * kRsm / 4.0f;
  std::vector<gpu::Vsgl> vsgls;
  for (glm::vec2 c : {glm::vec2(0.25f, 0.25f), glm::vec2(0.75f, 0.25f), glm::vec2(0.25f, 0.75f),
                      glm::vec2(0.75f, 0.75f)})
    vsgls.push_back(kernelVsgl(c, 3.0f, quadrant));
  const std::vector<double> weights =
      truth::kernelTexelWeights(vsgls, {kRsm, std::vector<uint32_t>(vsgls.size(), 1)}, vpls);
  ASSERT_EQ(weights.size(), 2u * kRsm * kRsm);
  for (size_t t = 0; t < weights.size(); ++t)
    EXPECT_NEAR(weights[t], t < kRsm * kRsm ? 0.0 : 1.0, 1e-12) << "texel " << t;
}

// The numeric SG stage against the analytic twin on the Cornell box with a few VSGLs: the
// analytic diffuse term is within 1e-3 of quadrature (sg-lighting.md), the glossy one within
// 23-38 % per pixel; the image sums must agree within 3 %, the shadowed image never exceeds the
// unshadowed one, and shadows must remove something (the boxes occlude).
TEST(ErrorBudget, NumericSgStageMatchesTheAnalyticTwin) {
  const engine::Scene scene = engine::makeBuiltinScene("cornell");
  const engine::View view = engine::cameraView(scene.cameras.at(0), 48, 27);
  const truth::EmbreeScene rays(scene);
  std::vector<gpu::Vsgl> vsgls;
  const engine::Bounds b = scene.bounds();
  const glm::vec3 lo = b.min, size = b.max - b.min;
  for (int i = 0; i < 6; ++i) {
    gpu::Vsgl v{};
    const glm::vec3 floor =
        lo + size * glm::vec3(0.2f + 0.12f * float(i), 0.0005f, 0.3f + 0.07f * float(i));
    v.diffuse = testing_gpu::vsglLobe(floor, 0.01f, {0, 1, 0}, 2.2925f, glm::vec3(2.0f));
    v.specular = testing_gpu::vsglLobe(floor, 0.01f, {0.3f, 1.0f, 0.2f}, 20.0f, glm::vec3(0.3f));
    vsgls.push_back(v);
  }
  truth::VsglStageSettings settings;
  settings.samplesPerLobe = 64;
  const truth::VsglStageImages stages = truth::vsglStages(scene, rays, view, vsgls, settings);
  double numeric = 0.0, analytic = 0.0, unshadowed = 0.0;
  for (size_t i = 0; i < stages.numeric.size(); ++i) {
    for (int c = 0; c < 3; ++c)
      EXPECT_LE(stages.numeric[i][c], stages.unshadowed[i][c] * (1 + 1e-12));
    numeric += stages.numeric[i].r + stages.numeric[i].g + stages.numeric[i].b;
    analytic += stages.analytic[i].r + stages.analytic[i].g + stages.analytic[i].b;
    unshadowed += stages.unshadowed[i].r + stages.unshadowed[i].g + stages.unshadowed[i].b;
  }
  std::printf("numeric %.6g, analytic %.6g (ratio %.4f), unshadowed %.6g\n", numeric, analytic,
              numeric / analytic, unshadowed);
  ASSERT_GT(analytic, 0.0);
  EXPECT_NEAR(numeric / analytic, 1.0, 0.03);
  EXPECT_LT(numeric, 0.99 * unshadowed);
}

// On the Cornell box the spot lights the floor (and the back wall): floor pixels are coplanar
// with it, the lines where surfaces meet are contact, and the side walls' middles are neither.
TEST(ErrorBudget, RegionsFindTheLitFloorAndTheContactLines) {
  const engine::Scene scene = engine::makeBuiltinScene("cornell");
  const engine::View view = engine::cameraView(scene.cameras.at(0), 64, 36);
  const truth::EmbreeScene rays(scene);
  const std::vector<truth::Vpl> vpls = truth::rsmVpls(scene, rays, 0, 32);
  const std::vector<truth::BudgetRegion> regions = truth::budgetRegions(scene, rays, view, vpls);
  size_t counts[4] = {0, 0, 0, 0};
  for (truth::BudgetRegion r : regions) ++counts[int(r)];
  std::printf("background %zu, coplanar %zu, contact %zu, rest %zu\n", counts[0], counts[1],
              counts[2], counts[3]);
  const size_t pixels = regions.size();
  EXPECT_GT(counts[1], pixels / 10);  // the floor
  EXPECT_GT(counts[2], pixels / 20);  // the room's edges and the boxes' feet
  EXPECT_GT(counts[3], pixels / 5);   // the walls' middles
  // The floor at the bottom left, away from walls and boxes, lies under the lit floor; the left
  // wall's middle is rest; the floor-wall line at the bottom left is contact.
  EXPECT_EQ(regions[size_t{35} * 64 + 10], truth::BudgetRegion::Coplanar);
  EXPECT_EQ(regions[size_t{14} * 64 + 4], truth::BudgetRegion::Rest);
  EXPECT_EQ(regions[size_t{34} * 64 + 2], truth::BudgetRegion::Contact);
}

// Area visibility: one VSGL whose kernel covers a 16^2 RSM whose left half of VPLs lies on the
// Cornell box's floor at one point and whose right half at another, the tall box between them
// for part of the room. The one-ray stage is all or nothing per pixel (one VSGL); the area stage
// is what the two points see, weighted by their transfer: the full unshadowed light where both
// see the receiver, none where neither does, and a share strictly between where one does. It
// never exceeds the unshadowed light.
TEST(ErrorBudget, AreaVisibilityIsWhatTheKernelsOwnVplsSee) {
  const engine::Scene scene = engine::makeBuiltinScene("cornell");
  const engine::View view = engine::cameraView(scene.cameras.at(0), 48, 27);
  const truth::EmbreeScene rays(scene);
  const engine::Bounds b = scene.bounds();
  const glm::dvec3 lo = b.min, size = b.max - b.min;
  const glm::dvec3 left = lo + size * glm::dvec3(0.15, 0.0, 0.5);
  const glm::dvec3 right = lo + size * glm::dvec3(0.85, 0.0, 0.5);
  std::vector<truth::Vpl> vpls = uniformVpls();
  for (truth::Vpl& v : vpls) {
    v.position = v.texel % kRsm < kRsm / 2 ? left : right;
    v.area = 1e-4;
  }
  gpu::Vsgl vsgl = kernelVsgl({0.5f, 0.5f}, 4.0f, 0.5f * kRsm * kRsm);
  vsgl.diffuse.meanVariance = glm::vec4(glm::vec3(0.5 * (left + right)), 0.01f);
  vsgl.visibilityPoint = glm::vec4(glm::vec3(left), 1.0f);
  truth::VsglStageSettings settings;
  settings.samplesPerLobe = 16;
  settings.kernelVpls = &vpls;
  settings.kernels.rsmSize = kRsm;
  const truth::VsglStageImages stages = truth::vsglStages(scene, rays, view, {vsgl}, settings);
  ASSERT_EQ(stages.areaVisible.size(), stages.unshadowed.size());
  size_t all = 0, none = 0, part = 0;
  for (size_t i = 0; i < stages.unshadowed.size(); ++i) {
    const double u = stages.unshadowed[i].g, a = stages.areaVisible[i].g, n = stages.numeric[i].g;
    if (!(u > 0.0)) continue;
    EXPECT_TRUE(n == 0.0 || n == u) << "pixel " << i;  // one ray: all or nothing
    EXPECT_GE(a, 0.0);
    EXPECT_LE(a, u * (1.0 + 1e-12)) << "pixel " << i;
    all += a >= u * (1.0 - 1e-12);
    none += a == 0.0;
    part += a > 0.0 && a < u * (1.0 - 1e-12);
  }
  std::printf("receivers lit by both points %zu, by neither %zu, by one %zu\n", all, none, part);
  EXPECT_GT(all, 50u);
  EXPECT_GT(part, 20u);
  EXPECT_GT(none, 0u);
}

// The flat share of the unshadowed SG image is the image of the flat VSGLs alone: a flat floor
// VSGL (sharpness VSGL_FLAT_SHARPNESS) is counted whole, a corner's (VSGL_CORNER_SHARPNESS) not.
TEST(ErrorBudget, FlatShareIsTheFlatVsglsLight) {
  const engine::Scene scene = engine::makeBuiltinScene("cornell");
  const engine::View view = engine::cameraView(scene.cameras.at(0), 32, 18);
  const truth::EmbreeScene rays(scene);
  const engine::Bounds b = scene.bounds();
  const glm::vec3 lo = b.min, size = b.max - b.min;
  gpu::Vsgl flat{}, corner{};
  flat.diffuse = testing_gpu::vsglLobe(lo + size * glm::vec3(0.4f, 0.001f, 0.4f), 0.01f, {0, 1, 0},
                                       float(VSGL_FLAT_SHARPNESS), glm::vec3(2.0f));
  corner.diffuse = testing_gpu::vsglLobe(lo + size * glm::vec3(0.05f, 0.05f, 0.5f), 0.01f,
                                         {1, 1, 0}, float(VSGL_CORNER_SHARPNESS), glm::vec3(2.0f));
  EXPECT_TRUE(truth::flatVsgl(flat));
  EXPECT_FALSE(truth::flatVsgl(corner));
  truth::VsglStageSettings settings;
  settings.samplesPerLobe = 8;
  const truth::VsglStageImages both =
      truth::vsglStages(scene, rays, view, {flat, corner}, settings);
  // The corner without power beside the flat VSGL keeps the numeric integration's per-VSGL
  // sample patterns the same in both runs.
  gpu::Vsgl dark = corner;
  dark.diffuse.power = glm::vec4(0.0f);
  const truth::VsglStageImages alone = truth::vsglStages(scene, rays, view, {flat, dark}, settings);
  EXPECT_TRUE(both.areaVisible.empty());  // no kernel VPLs given
  double flatLight = 0.0, cornerLight = 0.0;
  for (size_t i = 0; i < both.unshadowed.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(both.unshadowedFlat[i][c], alone.unshadowed[i][c]);
    flatLight += both.unshadowedFlat[i].g;
    cornerLight += both.unshadowed[i].g - both.unshadowedFlat[i].g;
  }
  EXPECT_GT(flatLight, 0.0);
  EXPECT_GT(cornerLight, 0.0);
}
