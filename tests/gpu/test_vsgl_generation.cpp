// VSGL generation on the GPU against its CPU twins: the attribute pyramids of an RSM
// (conservation of power through the exact-mean mips, isolation of non-finite texels, every
// channel of level 0), and the VSGLs generated from them with both kernel rules.
#include <cmath>
#include <cstring>

#include "engine/builtin_scenes.h"
#include "engine/commands.h"
#include "gi/settings.h"
#include "gpu_fixture.h"
#include "passes/vsgl_attributes.h"
#include "passes/vsgl_generate.h"
#include "reference/vsgl_attributes_reference.h"
#include "reference/vsgl_sampling.h"
#include "rsm_rig.h"

namespace {

class VsglAttributesTest : public testing_gpu::GpuTest {
 protected:
  static constexpr uint32_t kSize = 64;

  void SetUp() override {
    testing_gpu::GpuTest::SetUp();
    if (IsSkipped()) return;
    rig_ = std::make_unique<testing_gpu::RsmRig>(ctx(), "cornell", kSize);
  }

  void buildAttributes(bool broadReflections = false) {
    rig_->buildAttributes(ctx(), broadReflections);
  }

  // Level 0 of every pyramid against the twin; `glossy` gets the glossy lobe's total weight.
  void checkLevelZero(bool broadReflections, double* glossy);

  std::unique_ptr<testing_gpu::RsmRig> rig_;
};

TEST_F(VsglAttributesTest, TopLevelTimesTexelCountConservesRsmPower) {
  // The 1x1 level is the mean of all texels: times M it must give back the RSM's total
  // reflected power, within the pyramid's fp32 bound 2 L u (L = 6 levels) = 7.2e-7 relative.
  buildAttributes();
  auto diffuse = rig_->rsm->diffuseFlux().readbackRgba32f(ctx(), 0);
  auto specular = rig_->rsm->specularFlux().readbackRgba32f(ctx(), 0);
  glm::dvec3 totalDiffuse(0.0), totalSpecular(0.0);
  for (size_t i = 0; i < diffuse.size(); ++i) {
    totalDiffuse += glm::dvec3(diffuse[i]);
    totalSpecular += glm::dvec3(specular[i]);
  }
  const double m = double(kSize) * kSize, bound = 2.0 * 6.0 * std::ldexp(1.0, -24);
  auto topDiffuse =
      rig_->attributes->pyramid(VSGL_ATTR_DIFFUSE_POWER).readbackRgba32f(ctx(), 6).at(0);
  auto topSpecular =
      rig_->attributes->pyramid(VSGL_ATTR_SPECULAR_POWER).readbackRgba32f(ctx(), 6).at(0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(topDiffuse[k] * m, totalDiffuse[k], bound * totalDiffuse[k]) << "channel " << k;
    EXPECT_NEAR(topSpecular[k] * m, totalSpecular[k], bound * totalSpecular[k]) << "channel " << k;
  }
  EXPECT_GT(totalDiffuse.g, 0.0);
  EXPECT_GT(totalSpecular.g, 0.0);
}

// Both ways of Settings::broadReflections: the Cornell box's matte walls (roughness 0.9) and
// glossy ones (0.2, 0.25) put texels at both ends of the glossy share.
TEST_F(VsglAttributesTest, MatchesReferenceAtLevelZero) {
  double glossy[2] = {0.0, 0.0};
  for (bool broad : {true, false}) {
    SCOPED_TRACE(broad ? "broad reflections in the diffuse lobe" : "every reflection glossy");
    checkLevelZero(broad, &glossy[broad]);
  }
  // The matte walls' reflections moved to the diffuse lobe, the glossy walls' stayed.
  EXPECT_LT(glossy[true], 0.9 * glossy[false]);
  EXPECT_GT(glossy[true], 0.0);
}

void VsglAttributesTest::checkLevelZero(bool broadReflections, double* glossy) {
  buildAttributes(broadReflections);
  gi::RsmImages rsm{rig_->rsm->position().readbackRgba32f(ctx(), 0),
                    rig_->rsm->diffuseFlux().readbackRgba32f(ctx(), 0),
                    rig_->rsm->specularFlux().readbackRgba32f(ctx(), 0),
                    engine::readbackGBuffer(ctx(), rig_->rsm->surface())};
  auto ref = gi::vsglAttributesReference(rsm, rig_->view, broadReflections);
  // fp32 products of a handful of roundings against double: 1e-5 relative per channel, with an
  // absolute floor of 1e-6 of the channel's largest magnitude (axis components near zero).
  // The specular axis also goes through the fp32 lobe and Banerjee inverse (errors near 1e-5
  // of the mean length for sharp lobes, see vsgl_lobes.glsl), so it gets 1e-4.
  for (int a = 0; a < VSGL_ATTR_COUNT; ++a) {
    SCOPED_TRACE("attribute " + std::to_string(a));
    auto gpu = rig_->attributes->pyramid(a).readbackRgba32f(ctx(), 0);
    double largest = 0.0;
    for (const auto& v : ref[a])
      for (int k = 0; k < 4; ++k) largest = std::max(largest, std::abs(v[k]));
    const double rel = a == VSGL_ATTR_SPECULAR_AXIS ? 1e-4 : 1e-5;
    for (size_t i = 0; i < gpu.size(); ++i)
      for (int k = 0; k < 4; ++k)
        ASSERT_NEAR(gpu[i][k], ref[a][i][k], rel * std::abs(ref[a][i][k]) + 1e-6 * largest)
            << "texel " << i << " channel " << k;
    if (a == VSGL_ATTR_SPECULAR_POWER)
      for (const glm::vec4& t : gpu) *glossy += t.a;
  }
}

TEST_F(VsglAttributesTest, ANonFiniteTexelDoesNotPoisonThePyramid) {
  // Inject a NaN and an Inf into two lit RSM texels: they must contribute zero, and every level
  // of every pyramid must stay finite (vsgl-math.md section 12, case 14).
  auto diffuse = rig_->rsm->diffuseFlux().readbackRgba32f(ctx(), 0);
  auto position = rig_->rsm->position().readbackRgba32f(ctx(), 0);
  std::vector<size_t> lit;
  for (size_t i = 0; i < position.size() && lit.size() < 2; ++i)
    if (position[i].w > 0.0f) lit.push_back(i);
  ASSERT_EQ(lit.size(), 2u);
  diffuse[lit[0]].g = std::nanf("");
  position[lit[1]].x = INFINITY;
  rig_->rsm->diffuseFlux().upload(ctx(), diffuse.data(), diffuse.size() * sizeof(glm::vec4));
  rig_->rsm->position().upload(ctx(), position.data(), position.size() * sizeof(glm::vec4));
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    engine::imageBarrier(cmd, rig_->rsm->diffuseFlux(), VK_IMAGE_LAYOUT_GENERAL);
    engine::imageBarrier(cmd, rig_->rsm->position(), VK_IMAGE_LAYOUT_GENERAL);
  });
  buildAttributes();
  for (int a = 0; a < VSGL_ATTR_COUNT; ++a) {
    auto base = rig_->attributes->pyramid(a).readbackRgba32f(ctx(), 0);
    EXPECT_EQ(base[lit[0]], glm::vec4(0.0f)) << "attribute " << a;
    EXPECT_EQ(base[lit[1]], glm::vec4(0.0f)) << "attribute " << a;
    for (uint32_t level = 0; level < rig_->attributes->pyramid(a).desc().mips; ++level)
      for (const glm::vec4& v : rig_->attributes->pyramid(a).readbackRgba32f(ctx(), level))
        ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) &&
                    std::isfinite(v.w))
            << "attribute " << a << " level " << level;
  }
}

// Generation from the GPU's own attribute pyramids: the reference rebuilds exact double means
// from the GPU's level 0 and runs warp, kernel sizing and construction in double.
// Tolerances: positions in [0,1]^2 agree to 2e-5 (fp32 rescaling through 6 warp levels plus the
// lattice's fixed-point second coordinate, ~5e-7); levels to 2e-3 (the bisection's resolution
// L / 2^13 = 7e-4 plus fp32 masses); powers and means to 1e-3 relative (a 2e-3 level change
// moves the trilinear blend by that much at most on these smooth maps). A VSGL whose warp split
// or bisection step sits within fp32 noise of its threshold can take the other branch: such
// tie flips are counted and must stay under 2 % of N. The VPL baseline's point rule reads one
// texel at its centre: its disc variances (a / (4 pi), of order 1e-5 m^2 here) are held to 1e-3
// relative without the absolute floor of the means.
TEST_F(VsglAttributesTest, GeneratedVsglsMatchReferenceForEveryRule) {
  buildAttributes();
  std::array<gi::VectorPyramid, VSGL_ATTR_COUNT> pyramids;
  std::vector<double> pdfBase;
  for (int a = 0; a < VSGL_ATTR_COUNT; ++a) {
    auto base = rig_->attributes->pyramid(a).readbackRgba32f(ctx(), 0);
    std::vector<glm::dvec4> wide(base.begin(), base.end());
    if (a == VSGL_ATTR_DIFFUSE_AXIS)
      for (const glm::dvec4& v : wide) pdfBase.push_back(v.w);
    pyramids[a] = gi::makeVectorPyramid(wide, kSize);
  }
  gi::ScalarPyramid pdf = gi::makeScalarPyramid(pdfBase, kSize);
  gi::VsglGenerator generator(ctx(), 1024);
  const gi::TexelPatch patch{glm::dvec3(rig_->view.axis), rig_->view.texelArea,
                             rig_->view.perspective};
  for (uint32_t rule : {VSGL_RULE_TOK15, VSGL_RULE_MODIFIED, VSGL_RULE_POINT}) {
    for (const auto& [n, tolerance] : {std::pair{64u, 0.0f}, std::pair{1000u, 0.0f},
                                       std::pair{64u, gi::Settings{}.surfaceTolerance},
                                       std::pair{1000u, gi::Settings{}.surfaceTolerance}}) {
      SCOPED_TRACE("rule " + std::to_string(rule) + " N " + std::to_string(n) + " tolerance " +
                   std::to_string(tolerance));
      gi::VsglSettings settings{n, 1.0f, rule, 0, tolerance};
      ctx().submitAndWait([&](VkCommandBuffer cmd) {
        generator.record(cmd, *rig_->attributes, rig_->view, settings);
      });
      auto gpu = generator.vsgls().readbackAs<gpu::Vsgl>(ctx());
      const glm::dvec3 origin(rig_->view.origin);
      auto ref = gi::generateVsglsReference(pyramids, pdf, origin, n, 1.0, rule, patch, tolerance);
      // The boxes' tops beside the floor in the spot's image: kernels that leave their surface,
      // which the tolerance must shrink (the point rule reads one texel and ignores it).
      if (tolerance > 0.0f && rule != VSGL_RULE_POINT) {
        const auto unshrunk = gi::generateVsglsReference(pyramids, pdf, origin, n, 1.0, rule);
        size_t shrunk = 0;
        for (uint32_t i = 0; i < n; ++i) shrunk += ref[i].kernel.z < unshrunk[i].kernel.z - 0.01f;
        std::printf("rule %u N %u: %zu kernels shrunk onto their surface\n", rule, n, shrunk);
        EXPECT_GT(shrunk, n / 50);
      }
      size_t flips = 0;
      glm::dvec3 gpuTotal(0.0), refTotal(0.0);
      for (uint32_t i = 0; i < n; ++i) {
        const gpu::Vsgl &g = gpu[i], &r = ref[i];
        gpuTotal += glm::dvec3(g.diffuse.power) + glm::dvec3(g.specular.power);
        refTotal += glm::dvec3(r.diffuse.power) + glm::dvec3(r.specular.power);
        bool same = glm::length(glm::dvec2(g.kernel) - glm::dvec2(r.kernel)) < 2e-5 &&
                    std::abs(g.kernel.z - r.kernel.z) < 2e-3;
        if (!same) {
          ++flips;
          continue;
        }
        for (const auto& [gl, rl] :
             {std::pair{g.diffuse, r.diffuse}, std::pair{g.specular, r.specular}}) {
          for (int k = 0; k < 4; ++k) {
            ASSERT_NEAR(gl.power[k], rl.power[k], 1e-3 * std::abs(rl.power[k]) + 1e-9)
                << "VSGL " << i;
            const double floor = rule == VSGL_RULE_POINT && k == 3 ? 0.0 : 1e-4;
            ASSERT_NEAR(gl.meanVariance[k], rl.meanVariance[k],
                        1e-3 * std::abs(rl.meanVariance[k]) + floor)
                << "VSGL " << i;
          }
          ASSERT_TRUE(std::isfinite(gl.axisSharpness.w)) << "VSGL " << i;
        }
        // The ISM's centre: a bilinear level-0 fetch, so the means' tolerance.
        ASSERT_EQ(g.visibilityPoint.w, r.visibilityPoint.w) << "VSGL " << i;
        for (int k = 0; k < 3; ++k)
          ASSERT_NEAR(g.visibilityPoint[k], r.visibilityPoint[k],
                      1e-3 * std::abs(r.visibilityPoint[k]) + 1e-4)
              << "VSGL " << i;
      }
      std::printf("rule %u N %u: %zu tie flips, total power gpu %.6f ref %.6f\n", rule, n, flips,
                  gpuTotal.g, refTotal.g);
      EXPECT_LE(flips, std::max<size_t>(1, n / 50));
      EXPECT_NEAR(gpuTotal.g, refTotal.g, 1e-3 * refTotal.g);
    }
  }
}

TEST_F(VsglAttributesTest, ModifiedFisAndTheVplsConserveTheRsmPower) {
  // Modified FIS (vsgl-math.md 5.3) shares the RSM's power among the VSGLs: the sum is within
  // 2 % of the total for a PDF proportional to power (the energy test), and with
  // K >= N every VSGL holds exactly total / N. The VPL baseline's estimator Phi / (N p) is
  // unbiased, and on the stratified lattice its sum lands as close; so does modified FIS with
  // kernels shrunk onto their surfaces (the same estimator at a lower level).
  buildAttributes();
  auto top = rig_->attributes->pyramid(VSGL_ATTR_DIFFUSE_POWER).readbackRgba32f(ctx(), 6).at(0);
  const double total = double(top.g) * kSize * kSize;
  gi::VsglGenerator generator(ctx(), 1024);
  for (const auto& [rule, tolerance] :
       {std::pair{VSGL_RULE_MODIFIED, 0.0f}, std::pair{VSGL_RULE_POINT, 0.0f},
        std::pair{VSGL_RULE_MODIFIED, gi::Settings{}.surfaceTolerance}})
    for (uint32_t n : {64u, 256u, 1024u}) {
      ctx().submitAndWait([&](VkCommandBuffer cmd) {
        generator.record(cmd, *rig_->attributes, rig_->view, {n, 1.0f, rule, 0, tolerance});
      });
      auto v = generator.vsgls().readbackAs<gpu::Vsgl>(ctx());
      double sum = 0.0;
      for (uint32_t i = 0; i < n; ++i) sum += v[i].diffuse.power.g;
      std::printf("rule %u tolerance %.1f N %u: diffuse power %.6f of RSM %.6f (%.3f %%)\n", rule,
                  tolerance, n, sum, total, 100.0 * (sum / total - 1.0));
      EXPECT_NEAR(sum, total, 0.02 * total) << "rule " << rule << " N " << n;
    }
  const uint32_t n = 16;
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    generator.record(cmd, *rig_->attributes, rig_->view, {n, float(n), VSGL_RULE_MODIFIED});
  });
  auto v = generator.vsgls().readbackAs<gpu::Vsgl>(ctx());
  for (uint32_t i = 0; i < n; ++i)
    EXPECT_NEAR(v[i].diffuse.power.g, total / n, 1e-5 * total / n) << "VSGL " << i;
}

TEST_F(VsglAttributesTest, AnAllZeroRsmGivesFiniteVsglsWithoutPower) {
  // The light sees nothing (vsgl-math.md section 12, case 1): every RSM image is zero, so the PDF
  // is zero everywhere. Warping falls back to even splits, kernels take the top level, and
  // every VSGL must come out finite with zero power, for every rule.
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    VkClearColorValue zero{};
    VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    engine::computeToTransferBarrier(cmd);
    for (engine::Image* image :
         {&rig_->rsm->position(), &rig_->rsm->diffuseFlux(), &rig_->rsm->specularFlux()})
      vkCmdClearColorImage(cmd, image->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    engine::transferToComputeBarrier(cmd);
  });
  buildAttributes();
  gi::VsglGenerator generator(ctx(), 64);
  for (uint32_t rule : {VSGL_RULE_TOK15, VSGL_RULE_MODIFIED, VSGL_RULE_POINT}) {
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      generator.record(cmd, *rig_->attributes, rig_->view, {64, 1.0f, rule});
    });
    auto v = generator.vsgls().readbackAs<gpu::Vsgl>(ctx());
    for (uint32_t i = 0; i < 64; ++i) {
      const float* f = &v[i].diffuse.meanVariance.x;
      for (size_t k = 0; k < sizeof(gpu::Vsgl) / sizeof(float); ++k)
        ASSERT_TRUE(std::isfinite(f[k])) << "rule " << rule << " VSGL " << i << " float " << k;
      EXPECT_EQ(v[i].diffuse.power, glm::vec4(0.0f));
      EXPECT_EQ(v[i].specular.power, glm::vec4(0.0f));
    }
  }
}

}  // namespace
