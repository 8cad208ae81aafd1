// The view-dependent BRSM PDF (stage A importance VSGLs from the camera, stage B evaluation at
// the RSM cells and the mixed PDF) against its CPU twin, and its guarantees: every lit texel
// keeps p > 0, unlit texels and padding none, mean 1, finite for singular importance, and the
// flux PDF when there is no importance at all.
#include <cmath>

#include "engine/builtin_scenes.h"
#include "gpu_fixture.h"
#include "passes/brsm_pdf.h"
#include "reference/brsm_reference.h"

namespace {

class BrsmPdfTest : public testing_gpu::GpuTest {
 protected:
  static constexpr uint32_t kRsm = 64;
  static constexpr uint32_t kWidth = 96, kHeight = 64;
  static constexpr uint32_t kImportance = 128;

  void SetUp() override {
    testing_gpu::GpuTest::SetUp();
    if (IsSkipped()) return;
    scene_ = engine::makeBuiltinScene("cornell");
    light_ = scene_.lights.at(0);
    view_ = gi::makeRsmView(scene_, light_, kRsm);
    camera_ = scene_.cameras.at(0);
    cameraView_ = engine::cameraView(camera_, kWidth, kHeight);
    gpuScene_ = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx(), scene_));
    rasterizer_ = std::make_unique<engine::Rasterizer>(ctx());
    resolve_ = std::make_unique<engine::GBufferResolve>(ctx());
    mips_ = std::make_unique<gi::MipPyramid>(ctx());
    rsm_ = std::make_unique<gi::ReflectiveShadowMap>(ctx(), kRsm);
    attributes_ = std::make_unique<gi::VsglAttributes>(ctx(), kRsm);
    gbuffer_ = std::make_unique<engine::GBuffer>(engine::createGBuffer(ctx(), kWidth, kHeight));
    visibility_ = std::make_unique<engine::Buffer>(
        ctx(), engine::Rasterizer::visibilityBytes(kWidth, kHeight),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
    importance_ = std::make_unique<gi::ImportanceVsgls>(ctx(), kWidth, kHeight, kImportance);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      rasterizer_->record(cmd, *gpuScene_, cameraView_.viewProj,
                          {visibility_.get(), 0, kWidth, kHeight});
      resolve_->record(cmd, *gpuScene_, *visibility_, cameraView_, *gbuffer_);
      importance_->record(cmd, *gbuffer_, cameraView_, {kImportance, 1.0f, VSGL_RULE_MODIFIED},
                          *mips_);
    });
  }

  // The light's pyramids, freshly built (flux PDF), then stage B with `importance`. `specular`
  // false builds them without specular lobes (all zero); `evaluateSpecular` false evaluates
  // without them.
  void runBrsm(gi::BrsmPdf& brsm, const engine::Buffer& importance,
               const gi::BrsmSettings& settings, bool specular = true,
               bool evaluateSpecular = true) {
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      rsm_->record(cmd, *gpuScene_, *rasterizer_, *resolve_, view_, light_);
      attributes_->record(cmd, rsm_->vpls(), rsm_->surface(), view_, *mips_, nullptr, specular);
      brsm.record(cmd, *attributes_, view_, importance, settings, *mips_, nullptr,
                  evaluateSpecular);
    });
  }

  gi::AttributePyramids readLight() {
    gi::AttributePyramids p;
    for (int a = 0; a < VSGL_ATTR_COUNT; ++a) {
      p[a].size = kRsm;
      for (uint32_t level = 0; kRsm >> level >= 1; ++level) {
        std::vector<glm::dvec4> texels;
        for (const glm::vec4& t : attributes_->pyramid(a).readbackRgba32f(ctx(), level))
          texels.emplace_back(t);
        p[a].levels.push_back(std::move(texels));
      }
    }
    return p;
  }

  std::vector<double> gpuPdf() {
    std::vector<double> pdf;
    for (const glm::vec4& t :
         attributes_->pyramid(VSGL_ATTR_DIFFUSE_AXIS).readbackRgba32f(ctx(), 0))
      pdf.push_back(t.w);
    return pdf;
  }

  engine::Scene scene_;
  engine::Light light_;
  gi::RsmView view_;
  engine::Camera camera_;
  engine::View cameraView_;
  std::unique_ptr<engine::SceneGpu> gpuScene_;
  std::unique_ptr<engine::Rasterizer> rasterizer_;
  std::unique_ptr<engine::GBufferResolve> resolve_;
  std::unique_ptr<gi::MipPyramid> mips_;
  std::unique_ptr<gi::ReflectiveShadowMap> rsm_;
  std::unique_ptr<gi::VsglAttributes> attributes_;
  std::unique_ptr<engine::GBuffer> gbuffer_;
  std::unique_ptr<engine::Buffer> visibility_;
  std::unique_ptr<gi::ImportanceVsgls> importance_;
};

// Stage B per texel (grid = RSM) and on 16^2 cells of 4^2 texels, against the double twin.
// Tolerances: the cell sums are fp32 sums of 2 x 128 x 2 SG inner products whose exponents
// are O(10), each good to ~1e-6 relative; 2e-4 of the cell (plus 1e-6 of the largest cell, for
// cells whose sum is dominated by a few tiny terms) is two orders above that and far below the
// percent-level differences the PDF is for. The PDF inherits them through one division.
TEST_F(BrsmPdfTest, CellsAndPdfMatchTheReference) {
  const auto importance = importance_->vsgls().readbackAs<gpu::Vsgl>(ctx());
  for (uint32_t grid : {kRsm, 16u}) {
    const gi::BrsmSettings settings{kImportance, grid, 0.1f};
    gi::BrsmPdf brsm(ctx(), kRsm, grid);
    runBrsm(brsm, importance_->vsgls(), settings);
    const gi::AttributePyramids light = readLight();
    const auto ref = gi::brsmCellsReference(light, view_.origin, importance, grid);
    const auto cells = brsm.cells().readbackRgba32f(ctx(), 0);
    double largest = 0.0, worst = 0.0;
    size_t lit = 0;
    for (const glm::dvec4& c : ref) largest = std::max({largest, c.r, c.g});
    for (size_t i = 0; i < ref.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const double tolerance = 2e-4 * std::abs(ref[i][k]) + 1e-6 * largest;
        ASSERT_NEAR(cells[i][k], ref[i][k], tolerance) << "grid " << grid << " cell " << i;
        worst = std::max(worst, std::abs(cells[i][k] - ref[i][k]) / (std::abs(ref[i][k]) + 1e-300));
        lit += k == 0 && ref[i].b > 0.0;
      }
    std::printf("grid %u^2: %zu lit cells, worst relative difference %.2e\n", grid, lit, worst);
    ASSERT_GT(lit, ref.size() / 8) << "the spot lights too few cells for a meaningful test";

    const auto pdfRef = gi::brsmPdfReference(light, ref, grid, settings.fluxMix);
    const auto pdf = gpuPdf();
    for (size_t i = 0; i < pdf.size(); ++i)
      ASSERT_NEAR(pdf[i], pdfRef[i], 4e-4 * pdfRef[i] + 1e-7) << "grid " << grid << " texel " << i;
  }
}

// Without specular lobes (the planner's choice when no surface has one: the light's and the
// camera's specular pyramids are all zero) the pass reads only the diffuse lobes. It must match
// its twin, leave I_s = 0, and change nothing else: I_d, the cell means and the PDF are those of
// the full pass on the same inputs to the bit, since every term it drops is an exact zero.
TEST_F(BrsmPdfTest, WithoutSpecularLobesOnlyTheDiffuseImportanceIsEvaluated) {
  const gi::VsglSettings rule{kImportance, 1.0f, VSGL_RULE_MODIFIED};
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    importance_->record(cmd, *gbuffer_, cameraView_, rule, *mips_, nullptr, false);
  });
  const auto importance = importance_->vsgls().readbackAs<gpu::Vsgl>(ctx());
  size_t powered = 0;
  for (const gpu::Vsgl& v : importance) {
    ASSERT_EQ(v.specular.power.a, 0.0f) << "the premise: no specular importance";
    powered += v.diffuse.power.a > 0.0f;
  }
  ASSERT_GT(powered, kImportance / 2);
  const gi::BrsmSettings settings{kImportance, 16, 0.1f};
  gi::BrsmPdf brsm(ctx(), kRsm, settings.gridSize);
  runBrsm(brsm, importance_->vsgls(), settings, false, true);
  const auto fullCells = brsm.cells().readbackRgba32f(ctx(), 0);
  const auto fullPdf = gpuPdf();
  runBrsm(brsm, importance_->vsgls(), settings, false, false);
  const auto cells = brsm.cells().readbackRgba32f(ctx(), 0);
  const auto pdf = gpuPdf();
  const auto ref =
      gi::brsmCellsReference(readLight(), view_.origin, importance, settings.gridSize, false);
  double largest = 0.0;
  for (const glm::dvec4& c : ref) largest = std::max(largest, c.r);
  size_t lit = 0;
  for (size_t i = 0; i < cells.size(); ++i) {
    ASSERT_EQ(cells[i].r, fullCells[i].r) << "cell " << i;
    ASSERT_EQ(cells[i].b, fullCells[i].b) << "cell " << i;
    ASSERT_EQ(cells[i].g, 0.0f) << "cell " << i;
    ASSERT_EQ(ref[i].g, 0.0) << "cell " << i;
    // The tolerance of CellsAndPdfMatchTheReference.
    ASSERT_NEAR(cells[i].r, ref[i].r, 2e-4 * ref[i].r + 1e-6 * largest) << "cell " << i;
    lit += ref[i].r > 0.0;
  }
  ASSERT_GT(lit, cells.size() / 8) << "the spot lights too few cells for a meaningful test";
  for (size_t i = 0; i < pdf.size(); ++i) ASSERT_EQ(pdf[i], fullPdf[i]) << "texel " << i;
}

// Every texel with power keeps at least the flux share e w / mean_w; texels without power get
// nothing; the PDF has mean 1 (its pyramid top), which the generator's normalisation expects.
TEST_F(BrsmPdfTest, LitTexelsKeepTheFluxShareAndThePdfHasMeanOne) {
  const gi::BrsmSettings settings{kImportance, 16, 0.1f};
  gi::BrsmPdf brsm(ctx(), kRsm, settings.gridSize);
  runBrsm(brsm, importance_->vsgls(), settings);
  const auto diffuse = attributes_->pyramid(VSGL_ATTR_DIFFUSE_POWER).readbackRgba32f(ctx(), 0);
  const auto specular = attributes_->pyramid(VSGL_ATTR_SPECULAR_POWER).readbackRgba32f(ctx(), 0);
  double meanW = 0.0;
  for (size_t i = 0; i < diffuse.size(); ++i) meanW += double(diffuse[i].a) + specular[i].a;
  meanW /= double(diffuse.size());
  const auto pdf = gpuPdf();
  size_t lit = 0;
  for (size_t i = 0; i < pdf.size(); ++i) {
    const double w = double(diffuse[i].a) + specular[i].a;
    if (w > 0.0) {
      ++lit;
      ASSERT_GE(pdf[i], (1.0 - 1e-5) * settings.fluxMix * w / meanW) << "texel " << i;
    } else {
      ASSERT_EQ(pdf[i], 0.0) << "texel " << i;
    }
  }
  EXPECT_GT(lit, 0u);
  const float top = attributes_->pyramid(VSGL_ATTR_DIFFUSE_AXIS).readbackRgba32f(ctx(), 6).at(0).w;
  EXPECT_NEAR(top, 1.0, 1e-5);  // fp32 sums of 4096 terms of mean 1
}

// No importance at all (the camera sees nothing lit): the flux PDF, normalised to mean 1.
TEST_F(BrsmPdfTest, WithoutImportanceThePdfIsTheFluxPdf) {
  const std::vector<gpu::Vsgl> zero(kImportance, gpu::Vsgl{});
  engine::Buffer none(ctx(), sizeof(gpu::Vsgl) * zero.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      engine::MemoryUsage::GpuOnly);
  none.upload(ctx(), std::span<const gpu::Vsgl>(zero));
  gi::BrsmPdf brsm(ctx(), kRsm, 16);
  runBrsm(brsm, none, {kImportance, 16, 0.1f});
  const auto diffuse = attributes_->pyramid(VSGL_ATTR_DIFFUSE_POWER).readbackRgba32f(ctx(), 0);
  const auto specular = attributes_->pyramid(VSGL_ATTR_SPECULAR_POWER).readbackRgba32f(ctx(), 0);
  const float meanW =
      attributes_->pyramid(VSGL_ATTR_DIFFUSE_POWER).readbackRgba32f(ctx(), 6).at(0).a +
      attributes_->pyramid(VSGL_ATTR_SPECULAR_POWER).readbackRgba32f(ctx(), 6).at(0).a;
  const auto pdf = gpuPdf();
  for (size_t i = 0; i < pdf.size(); ++i) {
    const double flux = (double(diffuse[i].a) + specular[i].a) / meanW;
    ASSERT_NEAR(pdf[i], flux, 1e-6 * flux) << "texel " << i;
  }
}

// A zero-variance, isotropic importance lobe a couple of micrometres from a lit cell's receiver
// point is a near point singularity (vsgl-math.md section 12, case 12): its importance is huge
// (about 4e12 here, the premise checked below), and the PDF must stay finite and non-negative.
TEST_F(BrsmPdfTest, SingularImportanceKeepsThePdfFinite) {
  gi::BrsmPdf brsm(ctx(), kRsm, kRsm);
  runBrsm(brsm, importance_->vsgls(), {kImportance, kRsm, 0.1f});  // to find a lit texel
  const gi::AttributePyramids light = readLight();
  auto base = [&](int attribute, size_t texel) { return light[attribute].levels[0][texel]; };
  size_t texel = 0;
  while (!(base(VSGL_ATTR_DIFFUSE_POWER, texel).a > 0.0)) ++texel;
  // The cell's receiver point, as brsm_evaluate.comp forms it.
  const glm::dvec3 y =
      (glm::dvec3(base(VSGL_ATTR_DIFFUSE_POSITION, texel)) +
       glm::dvec3(base(VSGL_ATTR_SPECULAR_POSITION, texel))) /
      (base(VSGL_ATTR_DIFFUSE_POWER, texel).a + base(VSGL_ATTR_SPECULAR_POWER, texel).a);
  gpu::Vsgl spike{};
  spike.diffuse.meanVariance = glm::vec4(glm::dvec3(view_.origin) + y + glm::dvec3(1e-6), 0.0);
  spike.diffuse.axisSharpness = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);  // isotropic
  spike.diffuse.power = glm::vec4(1e3f);
  std::vector<gpu::Vsgl> single(1, spike);
  engine::Buffer buffer(ctx(), sizeof(gpu::Vsgl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        engine::MemoryUsage::GpuOnly);
  buffer.upload(ctx(), std::span<const gpu::Vsgl>(single));
  runBrsm(brsm, buffer, {1, kRsm, 0.1f});
  float largest = 0.0f;
  for (const glm::vec4& c : brsm.cells().readbackRgba32f(ctx(), 0)) {
    ASSERT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && c.r >= 0.0f);
    largest = std::max({largest, c.r, c.g});
  }
  std::printf("largest cell importance next to the spike: %.3g\n", double(largest));
  ASSERT_GT(largest, 1e9f) << "the spike must sit next to a receiver for the test to mean anything";
  for (double p : gpuPdf()) ASSERT_TRUE(std::isfinite(p) && p >= 0.0);
}

}  // namespace
