// VSGL shading (vsgl_shade.comp) against its double twin (reference/vsgl_shade_reference.cpp)
// on a real G-buffer, with VSGLs that include the hard cases of vsgl-math.md section 12 (zero
// variance, zero sharpness, a lobe without power, a receiver at a lobe's mean, huge power);
// and the far-field limit: a VSGL with a tiny variance far away shades like a point light.
// VSGL culling loses no more light than its budget.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/brdf_reference.h"
#include "engine/builtin_scenes.h"
#include "engine/commands.h"
#include "engine/gbuffer_reference.h"
#include "engine/rasterizer.h"
#include "gpu_fixture.h"
#include "passes/ism.h"
#include "passes/vsgl_shade.h"
#include "reference/ism_reference.h"
#include "reference/vpl_shade_reference.h"
#include "reference/vsgl_shade_reference.h"
#include "shared/vsgl_shade.h"
#include "test_vsgls.h"

namespace {

constexpr uint32_t kWidth = 48, kHeight = 32;

using testing_gpu::vsglLobe;

class VsglShadeTest : public testing_gpu::GpuTest {
 protected:
  void SetUp() override {
    testing_gpu::GpuTest::SetUp();
    if (IsSkipped()) return;
    scene_ = engine::makeBuiltinScene("cornell");
    view_ = engine::cameraView(scene_.cameras.at(0), kWidth, kHeight);
    gpuScene_ = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx(), scene_));
    gbuffer_ = std::make_unique<engine::GBuffer>(renderGBuffer(*gpuScene_, view_));
    decoded_ = engine::readbackGBuffer(ctx(), *gbuffer_);
  }

  struct Shaded {
    std::vector<glm::vec4> diffuse, glossy;
  };

  // Shades the G-buffer with `vsgls`; their ISMs are built from the scene first (read with
  // VSGL_SHADE_VISIBILITY, bound either way), and `atlas` receives them as tile-major distances.
  // With VSGL_SHADE_CULL, `cullBudget` is tau and `stats` receives the pass's counts.
  // `points`: the records are VPLs, shaded by vpl_shade.comp.
  Shaded shade(const std::vector<gpu::Vsgl>& vsgls, uint32_t flags,
               std::vector<double>* atlas = nullptr, float cullBudget = 0.0f,
               gpu::VsglShadeStats* stats = nullptr, bool points = false) {
    const auto count = static_cast<uint32_t>(vsgls.size());
    engine::Buffer buffer(ctx(), vsgls.size() * sizeof(gpu::Vsgl),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::Upload);
    buffer.upload(ctx(), vsgls.data(), vsgls.size() * sizeof(gpu::Vsgl));
    gi::Ism ism(ctx(), ismSettings_, count);
    gi::VsglShade pass(ctx());
    gi::IndirectImages out = gi::createIndirectImages(ctx(), gbuffer_->width, gbuffer_->height);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      ism.recordPoints(cmd, *gpuScene_);
      ism.recordBuild(cmd, *gpuScene_, buffer, count);
      engine::computeBarrier(cmd);
      gi::VsglShade::Inputs in{&buffer, count, flags, &ism.atlas(), ism.params()};
      in.cullBudget = cullBudget;
      in.points = points;
      pass.recordStatsReset(cmd);
      pass.record(cmd, *gbuffer_, view_, in, out);
      pass.recordStatsReadback(cmd);
    });
    if (stats) *stats = pass.lastStats();
    if (atlas) {
      params_ = ism.params();
      const auto bytes = ism.atlas().readback(ctx(), 0);
      const uint32_t width = ism.atlas().desc().width, size = ismSettings_.mapSize;
      std::vector<float> image(bytes.size() / 4);
      std::memcpy(image.data(), bytes.data(), bytes.size());
      atlas->clear();
      for (uint32_t k = 0; k < count; ++k) {
        const glm::uvec2 origin = ism.tileOrigin(k);
        for (uint32_t y = 0; y < size; ++y)
          for (uint32_t x = 0; x < size; ++x)
            atlas->push_back(image[size_t{origin.y + y} * width + origin.x + x]);
      }
    }
    return {out.diffuse.readbackRgba32f(ctx()), out.glossy.readbackRgba32f(ctx())};
  }

  // The receiver of pixel (x, y) as the shader rebuilds it, in double.
  gi::ShadeReceiver receiver(uint32_t x, uint32_t y) const {
    const engine::GBufferSample& s = decoded_.at(x, y);
    const glm::dmat4 inv(view_.invViewProj);
    const glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / glm::dvec2(kWidth, kHeight) * 2.0 - 1.0;
    auto unproject = [&](double z) {
      glm::dvec4 h = inv * glm::dvec4(ndc, z, 1.0);
      return glm::dvec3(h) / h.w;
    };
    gi::ShadeReceiver r;
    r.position = unproject(s.depth);
    r.view = -glm::normalize(unproject(0.5) - unproject(0.0));
    r.normal = s.normal;
    r.albedo = s.diffuse;
    r.f0 = s.f0;
    r.f90 = s.f90;
    r.roughness = s.roughness;
    return r;
  }

  // GPU against the double twin `cpu`, per pixel and channel, with MatchesReference's tolerance
  // (2e-3 of the value plus 1e-5 of the image's largest); every value must be finite. Without
  // `steps` the first few values over fail the test; with it (ISM visibility, whose depth test
  // may step on 1 % of the pixels) at most 1 % of the pixels may be over. The twin's image must
  // not be black (nor its glossy term, with `glossy`): a comparison of zeros would prove nothing.
  void expectMatches(const Shaded& gpu, const std::vector<gi::IndirectRadiance>& cpu, bool steps,
                     bool glossy, const std::string& label) const {
    double largest[2] = {0.0, 0.0};
    for (const gi::IndirectRadiance& r : cpu) {
      largest[0] = std::max({largest[0], r.diffuse.r, r.diffuse.g, r.diffuse.b});
      largest[1] = std::max({largest[1], r.glossy.r, r.glossy.g, r.glossy.b});
    }
    ASSERT_GT(largest[0], 0.0) << label;
    if (glossy) {
      ASSERT_GT(largest[1], 0.0) << label;
    }
    double worst[2] = {0.0, 0.0};
    size_t failures = 0, failedPixels = 0;
    for (size_t i = 0; i < cpu.size(); ++i) {
      bool pixelFailed = false;
      for (int term = 0; term < 2; ++term) {
        const glm::dvec3 want = term == 0 ? cpu[i].diffuse : cpu[i].glossy;
        const glm::dvec3 got(term == 0 ? gpu.diffuse[i] : gpu.glossy[i]);
        for (int c = 0; c < 3; ++c) {
          ASSERT_TRUE(std::isfinite(got[c])) << label << " pixel " << i;
          const double tolerance = 2e-3 * std::abs(want[c]) + 1e-5 * largest[term];
          const double error = std::abs(got[c] - want[c]);
          worst[term] = std::max(worst[term], error / tolerance);
          if (error <= tolerance) continue;
          pixelFailed = true;
          if (!steps && failures++ < 5)
            ADD_FAILURE() << label << ": " << (term ? "glossy" : "diffuse") << " pixel " << i
                          << " channel " << c << ": gpu " << got[c] << " cpu " << want[c];
        }
      }
      failedPixels += pixelFailed;
    }
    std::printf("%s: worst error / tolerance: diffuse %.3f, glossy %.3f; %zu pixels over\n",
                label.c_str(), worst[0], worst[1], failedPixels);
    if (steps) {
      EXPECT_LE(failedPixels, cpu.size() / 100) << label;
    }
  }

  // The far-field limit: against a point light of radiant intensity `intensity(-l)` (towards
  // the receiver) at `position`, per pixel facing it by more than `minCosine`, diffuse and
  // glossy to 1e-3 relative (a glossy value below 1e-6 of the diffuse one is left out). More
  // than a quarter of the pixels must be compared.
  template <typename Intensity>
  void expectPointLight(const Shaded& gpu, glm::vec3 position, double minCosine,
                        const Intensity& intensity, const char* label) const {
    size_t compared = 0;
    double worst = 0.0;
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        if (decoded_.at(x, y).background()) continue;
        const gi::ShadeReceiver r = receiver(x, y);
        const glm::dvec3 toLight = glm::dvec3(position) - r.position;
        const double d2 = glm::dot(toLight, toLight);
        const glm::dvec3 l = toLight / std::sqrt(d2);
        const double nl = glm::dot(r.normal, l);
        if (nl <= minCosine) continue;
        const glm::dvec3 irradiance = intensity(-l) * nl / d2;
        const glm::dvec3 diffuse = r.albedo / 3.141592653589793 * irradiance;
        const glm::dvec3 glossy =
            engine::ggxSpecular(r.normal, r.view, l, r.f0, r.f90, r.roughness) * irradiance;
        const size_t i = size_t{y} * kWidth + x;
        for (int c = 0; c < 3; ++c) {
          const double ed = std::abs(gpu.diffuse[i][c] - diffuse[c]) / diffuse[c];
          worst = std::max(worst, ed);
          EXPECT_LE(ed, 1e-3) << label << ": diffuse pixel " << x << "," << y;
          if (glossy[c] > 1e-6 * diffuse[c]) {
            const double eg = std::abs(gpu.glossy[i][c] - glossy[c]) / glossy[c];
            worst = std::max(worst, eg);
            EXPECT_LE(eg, 1e-3) << label << ": glossy pixel " << x << "," << y;
          }
        }
        ++compared;
      }
    std::printf("%s: %zu pixels, worst relative error %.2e\n", label, compared, worst);
    EXPECT_GT(compared, size_t{kWidth * kHeight / 4});
  }

  engine::Scene scene_;
  engine::View view_;
  std::unique_ptr<engine::SceneGpu> gpuScene_;
  std::unique_ptr<engine::GBuffer> gbuffer_;
  engine::GBufferData decoded_;
  gi::IsmSettings ismSettings_{32, 1u << 14, 1024};  // small maps: the test needs coverage only
  gpu::IsmParams params_{};
};

// VSGLs inside the Cornell box spanning the cases that stress the fp32 path.
std::vector<gpu::Vsgl> hardCaseVsgls(const engine::Scene& scene, const gi::ShadeReceiver& at) {
  const engine::Bounds b = scene.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max), extent = b.max - b.min;
  std::vector<gpu::Vsgl> vsgls;
  auto add = [&](gpu::VsglLobe d, gpu::VsglLobe s) {
    gpu::Vsgl v{};
    v.diffuse = d;
    v.specular = s;
    vsgls.push_back(v);
  };
  // A lattice of ordinary lobes pointing in assorted directions with assorted widths.
  for (int i = 0; i < 12; ++i) {
    const float t = float(i) / 12.0f;
    const glm::vec3 mean =
        centre + extent * glm::vec3(0.4f * std::cos(6.28f * t), 0.35f * (t - 0.5f),
                                    0.4f * std::sin(6.28f * t));
    const float fi = float(i);
    const glm::vec3 axis(std::sin(2.4f * fi), std::cos(1.7f * fi), std::sin(0.9f * fi + 1.0f));
    const float variance = 1e-4f * std::pow(10.0f, float(i % 4));
    add(vsglLobe(mean, variance, axis, 2.2925f, glm::vec3(1.0f, 0.7f, 0.4f)),
        vsglLobe(mean, variance, -axis, std::pow(10.0f, float(i % 5)),
                 glm::vec3(0.3f, 0.5f, 1.0f)));
  }
  // Zero variance (single texel), zero sharpness (opposing normals), no power in one lobe.
  add(vsglLobe(centre, 0.0f, {0, -1, 0}, 2.2925f, glm::vec3(2.0f)),
      vsglLobe(centre, 0.0f, {0, -1, 0}, 0.0f, glm::vec3(0.0f)));
  add(vsglLobe(centre + glm::vec3(0.1f), 1e-3f, {1, 0, 0}, 0.0f, glm::vec3(0.5f)),
      vsglLobe(centre, 1e-3f, {1, 0, 0}, 2.0e12f, glm::vec3(0.5f)));
  // A receiver at the lobe's mean (section 12, case 12) and huge power (case 5).
  add(vsglLobe(glm::vec3(at.position), 1e-6f, glm::vec3(at.normal), 2.2925f, glm::vec3(1.0f)),
      vsglLobe(centre - glm::vec3(0.2f), 1e-2f, {0, 1, 0}, 50.0f, glm::vec3(4e6f)));
  return vsgls;
}

// GPU vs double twin, per pixel and channel. Tolerance: 2e-3 of the value plus 1e-5 of the
// image's largest value. The GPU rebuilds positions from fp32 depth and its SG products run in
// fp32 (relative error ~1e-6 per operation, amplified by the sharpness d^2/v of narrow lobes,
// e.g. lambda = 1e4 turns a 1e-7 direction error into 1e-3 of exponent); the floor absorbs the
// same relative error on pixels that a much brighter pixel dominates. With visibility, the
// reference runs the ISM lookup in double on the GPU's own atlas; a receiver whose fp32 and
// double distances fall on opposite sides of a texel's depth test sees a different visibility
// (a step, not a rounding), so up to 1 % of the pixels may differ there.
TEST_F(VsglShadeTest, MatchesReference) {
  const uint32_t cx = kWidth / 2, cy = kHeight / 2;
  ASSERT_FALSE(decoded_.at(cx, cy).background());
  const std::vector<gpu::Vsgl> vsgls = hardCaseVsgls(scene_, receiver(cx, cy));
  for (uint32_t flags : {VSGL_SHADE_GLOSSY | VSGL_SHADE_PLANAR, VSGL_SHADE_PLANAR,
                         VSGL_SHADE_GLOSSY | VSGL_SHADE_VISIBILITY | VSGL_SHADE_PLANAR,
                         VSGL_SHADE_VISIBILITY, VSGL_SHADE_GLOSSY}) {
    const bool glossy = flags & VSGL_SHADE_GLOSSY, visible = flags & VSGL_SHADE_VISIBILITY;
    const bool planar = flags & VSGL_SHADE_PLANAR;
    std::vector<double> atlas;
    const Shaded gpu = shade(vsgls, flags, &atlas);
    std::vector<gi::IndirectRadiance> cpu(size_t{kWidth} * kHeight);
    size_t occluded = 0, pairs = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        if (decoded_.at(x, y).background()) continue;
        gi::IndirectRadiance& r = cpu[size_t{y} * kWidth + x];
        const gi::ShadeReceiver at = receiver(x, y);
        gi::VsglVisibility visibility;
        if (visible)
          visibility = [&](uint32_t k) {
            const double v = gi::ismVisibilityReference(
                atlas, params_, gi::ismFrameReference(vsgls[k], params_.centreOffset), k,
                at.position, at.normal);
            occluded += v < 1.0;
            ++pairs;
            return v;
          };
        r = gi::shadeReference(at, vsgls, glossy, planar, visibility);
      }
    if (visible) {
      std::printf("ISM: %zu of %zu pixel-VSGL pairs (partly) occluded\n", occluded, pairs);
      ASSERT_GT(occluded, pairs / 10) << "the visibility variant must test occlusion";
    }
    expectMatches(gpu, cpu, visible, glossy, "flags " + std::to_string(flags));
    if (!glossy) {
      for (const glm::vec4& g : gpu.glossy) EXPECT_EQ(glm::vec3(g), glm::vec3(0.0f));
    }
  }
}

// The largest VSGL count (gi::kMaxVsglCount) is shaded whole: lavapipe ends an invocation's
// loops after 65 535 iterations, and the shading loop once ran about ten per VSGL (the ISM
// filter's tap loops), so it stopped near 6 000 VSGLs. Pool subsets repeat every pointCount /
// pointsPerVsgl VSGLs, so 32 768 copies of one VSGL at 1 / 32 768 of its power see the same
// visibilities as 64 copies at 1 / 64, and must shade the same light, up to fp32 summation
// (1e-3 of the value, and 1e-6 of the image's largest for the dark pixels). Box 3 x 3 PCF, the
// filter with the most taps, and the glossy term; a 12 x 8 G-buffer keeps it to seconds.
TEST_F(VsglShadeTest, TheLargestCountIsShadedWhole) {
  const gpu::Vsgl one = hardCaseVsgls(scene_, receiver(kWidth / 2, kHeight / 2)).front();
  view_ = engine::cameraView(scene_.cameras.at(0), 12, 8);
  gbuffer_ = std::make_unique<engine::GBuffer>(renderGBuffer(*gpuScene_, view_));
  ismSettings_ = {16, 1u << 14, 256};
  ismSettings_.pcf = gi::IsmBox3;
  auto copies = [&](uint32_t n) {
    gpu::Vsgl v = one;
    v.diffuse.power /= float(n);
    v.specular.power /= float(n);
    return std::vector<gpu::Vsgl>(n, v);
  };
  const uint32_t flags = VSGL_SHADE_GLOSSY | VSGL_SHADE_VISIBILITY | VSGL_SHADE_PLANAR;
  const Shaded few = shade(copies(64), flags);
  const Shaded all = shade(copies(gi::kMaxVsglCount), flags);
  float largest = 0.0f;
  for (const glm::vec4& c : few.diffuse) largest = std::max({largest, c.r, c.g, c.b});
  ASSERT_GT(largest, 0.0f);
  for (size_t i = 0; i < few.diffuse.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(all.diffuse[i][k], few.diffuse[i][k], 1e-3f * few.diffuse[i][k] + 1e-6f * largest)
          << "pixel " << i;
      EXPECT_NEAR(all.glossy[i][k], few.glossy[i][k], 1e-3f * few.glossy[i][k] + 1e-6f * largest)
          << "pixel " << i;
    }
}

// KHR_materials_specular's strength s scales a dielectric's F0 and F90 alike, so the glossy
// term is s times the full-strength one (Schlick's F and the tabulated albedo are both linear in
// the pair; fp32 rounding only: 1e-5 relative), the diffuse term does not change (bit for bit),
// and at s = 0 the glossy term is gone (below 1e-6 of full strength: the SG fit's floors keep
// it a denormal rather than exactly 0). The CPU twin agrees at s = 0.5 (MatchesReference's
// tolerance), so the F90 path is checked on both sides.
TEST_F(VsglShadeTest, SpecularStrengthScalesTheGlossyTerm) {
  const std::vector<gpu::Vsgl> vsgls = hardCaseVsgls(scene_, receiver(kWidth / 2, kHeight / 2));
  const Shaded full = shade(vsgls, VSGL_SHADE_GLOSSY);
  Shaded scaled[2];
  for (int k = 0; k < 2; ++k) {
    engine::Scene weak = scene_;
    for (engine::Material& m : weak.materials) m.specularFactor = k == 0 ? 0.5f : 0.0f;
    const engine::SceneGpu gpu = engine::uploadScene(ctx(), weak);
    *gbuffer_ = renderGBuffer(gpu, view_);
    scaled[k] = shade(vsgls, VSGL_SHADE_GLOSSY);
    if (k == 0) decoded_ = engine::readbackGBuffer(ctx(), *gbuffer_);
  }
  double largest = 0.0;
  for (const glm::vec4& g : full.glossy) largest = std::max({largest, double(g.r), double(g.g)});
  ASSERT_GT(largest, 0.0);
  size_t checked = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = size_t{y} * kWidth + x;
      if (decoded_.at(x, y).background()) continue;
      EXPECT_EQ(decoded_.at(x, y).f90, 0.5);  // a dielectric: F90 = s
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(scaled[0].diffuse[i][c], full.diffuse[i][c]) << "pixel " << i;
        EXPECT_NEAR(scaled[0].glossy[i][c], 0.5f * full.glossy[i][c],
                    1e-5 * full.glossy[i][c] + 1e-7 * largest)
            << "pixel " << i;
        EXPECT_LE(scaled[1].glossy[i][c], 1e-6 * full.glossy[i][c] + 1e-12 * largest);
      }
      if (x % 4 == 0 && y % 4 == 0) {  // the twin on a sample of the pixels
        const gi::IndirectRadiance r = gi::shadeReference(receiver(x, y), vsgls, true, false);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(scaled[0].glossy[i][c], r.glossy[c], 2e-3 * r.glossy[c] + 1e-5 * largest)
              << "pixel " << x << "," << y;
        ++checked;
      }
    }
  EXPECT_GT(checked, 20u);
}

// vsgl-math.md section 12, case 18: as v -> 0 a VSGL lobe is a point light with intensity
// I(w) = Phi G(w; xi, lambda) / S(lambda), so the shading must match the point light's
// rho / pi (n . l) I / d^2 and f_s(l, v) (n . l) I / d^2 to 1e-3 (relative, per pixel). The
// lobe is 60 m away with v = 1e-12 m^2 (angular radius ~2e-8 rad, sharpness clamped at 2^41).
// Only pixels that face it (n . l > 0.2) are compared: at grazing incidence the [T24] cosine fit
// is not exact (docs/techniques/sg-lighting.md).
TEST_F(VsglShadeTest, FarTinyVarianceIsPointLight) {
  const engine::Bounds b = scene_.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max);
  const glm::vec3 mean = centre + glm::vec3(0.0f, 10.0f, 59.0f);
  const glm::vec3 axis = glm::normalize(centre - mean);
  const float sharpness = 20.0f;
  const glm::vec3 power(3.0e3f, 2.0e3f, 1.0e3f);
  gpu::Vsgl v{};
  v.diffuse = vsglLobe(mean, 1e-12f, axis, sharpness, power);
  v.specular = vsglLobe(mean, 1e-12f, axis, sharpness, glm::vec3(0.0f));
  const Shaded gpu = shade({v}, VSGL_SHADE_GLOSSY);  // no visibility: the lobe is outside the box
  expectPointLight(
      gpu, mean, 0.2,
      [&](glm::dvec3 toward) {
        return glm::dvec3(power) * gi::sgEvaluate(toward, glm::dvec3(axis), sharpness) /
               gi::sgIntegral(sharpness);
      },
      "point-light limit");
}

// VPLs as the point rule makes them (VSGL_RULE_POINT: one texel, both lobes at the same point
// with the disc's variance a / (4 pi)) inside the Cornell box, with the hard cases of the VPL
// shading: a VPL at the receiver (d = 0), one without diffuse power (no normal: the SG emitter),
// one without a disc (a = 0: the bare 1 / d^2), a near-mirror lobe (lambda = 1e4) and a rough one.
std::vector<gpu::Vsgl> hardCaseVpls(const engine::Scene& scene, const gi::ShadeReceiver& at) {
  const engine::Bounds b = scene.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max), extent = b.max - b.min;
  std::vector<gpu::Vsgl> vpls;
  auto add = [&](glm::vec3 position, glm::vec3 normal, float area, glm::vec3 diffuse,
                 glm::vec3 specularAxis, float sharpness, glm::vec3 specular) {
    gpu::Vsgl v{};
    const float variance = area / (4.0f * 3.14159265f);
    v.diffuse = vsglLobe(position, variance, normal, float(VSGL_FLAT_SHARPNESS), diffuse);
    v.specular = vsglLobe(position, variance, specularAxis, sharpness, specular);
    vpls.push_back(v);
  };
  for (int i = 0; i < 12; ++i) {
    const float t = float(i) / 12.0f, fi = float(i);
    const glm::vec3 position =
        centre + extent * glm::vec3(0.4f * std::cos(6.28f * t), 0.35f * (t - 0.5f),
                                    0.4f * std::sin(6.28f * t));
    const glm::vec3 normal(std::sin(2.4f * fi), std::cos(1.7f * fi), std::sin(0.9f * fi + 1.0f));
    add(position, normal, 1e-4f * std::pow(10.0f, float(i % 3)), glm::vec3(1.0f, 0.7f, 0.4f),
        normal + glm::vec3(0.3f, -0.2f, 0.1f), std::pow(10.0f, float(i % 5)),
        glm::vec3(0.3f, 0.5f, 1.0f));
  }
  add(glm::vec3(at.position), glm::vec3(at.normal), 1e-3f, glm::vec3(1.0f), glm::vec3(at.normal),
      10.0f, glm::vec3(0.5f));
  gpu::Vsgl dark{};  // no diffuse power: the record keeps no normal
  dark.diffuse = vsglLobe(centre, 0.0f, {0, 0, 1}, 0.0f, glm::vec3(0.0f));
  dark.diffuse.meanVariance = glm::vec4(0.0f);
  dark.specular =
      vsglLobe(centre + glm::vec3(0.0f, 0.3f, 0.0f), 1e-3f, {0, -1, 0.2f}, 30.0f, glm::vec3(2.0f));
  vpls.push_back(dark);
  add(centre - glm::vec3(0.2f), {0, 1, 0}, 0.0f, glm::vec3(0.5f), {0, 1, 0}, 2.0f, glm::vec3(0.2f));
  return vpls;
}

// vpl_shade.comp against its double twin, as MatchesReference with the same tolerances and the
// same reasons (fp32 positions, ISM steps on 1 % of the pixels), for each variant it reads.
TEST_F(VsglShadeTest, VplShadingMatchesReference) {
  const uint32_t cx = kWidth / 2, cy = kHeight / 2;
  ASSERT_FALSE(decoded_.at(cx, cy).background());
  const std::vector<gpu::Vsgl> vpls = hardCaseVpls(scene_, receiver(cx, cy));
  for (uint32_t flags : {VSGL_SHADE_GLOSSY, 0u, VSGL_SHADE_GLOSSY | VSGL_SHADE_VISIBILITY,
                         VSGL_SHADE_GLOSSY | VSGL_SHADE_DIFFUSE_LOBES | VSGL_SHADE_SKIP_SKY}) {
    const bool glossy = flags & VSGL_SHADE_GLOSSY, visible = flags & VSGL_SHADE_VISIBILITY;
    const bool diffuseOnly = flags & VSGL_SHADE_DIFFUSE_LOBES;
    std::vector<double> atlas;
    const Shaded gpu = shade(vpls, flags, &atlas, 0.0f, nullptr, true);
    std::vector<gi::IndirectRadiance> cpu(size_t{kWidth} * kHeight);
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        if (decoded_.at(x, y).background()) continue;
        const gi::ShadeReceiver at = receiver(x, y);
        gi::VsglVisibility visibility;
        if (visible)
          visibility = [&](uint32_t k) {
            return gi::ismVisibilityReference(atlas, params_,
                                              gi::ismFrameReference(vpls[k], params_.centreOffset),
                                              k, at.position, at.normal);
          };
        gi::IndirectRadiance& r = cpu[size_t{y} * kWidth + x];
        r = gi::shadeVplsReference(at, vpls, glossy, diffuseOnly, visibility);
      }
    expectMatches(gpu, cpu, visible, glossy, "VPL flags " + std::to_string(flags));
  }
}

// Far from every receiver a VPL is a point light with the Lambert emission of its surface: the
// disc's terms vanish (a / d^2 ~ 1e-8 here, below the 1e-3 tolerance of fp32 shading).
TEST_F(VsglShadeTest, FarVplIsLambertianPointLight) {
  const engine::Bounds b = scene_.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max);
  const glm::vec3 position = centre + glm::vec3(0.0f, 10.0f, 59.0f);
  const glm::vec3 normal = glm::normalize(centre - position + glm::vec3(3.0f, 0.0f, 0.0f));
  const glm::vec3 power(3.0e3f, 2.0e3f, 1.0e3f);
  gpu::Vsgl v{};
  v.diffuse =
      vsglLobe(position, 1e-3f / (4.0f * 3.14159265f), normal, float(VSGL_FLAT_SHARPNESS), power);
  v.specular = vsglLobe(position, v.diffuse.meanVariance.w, normal, 10.0f, glm::vec3(0.0f));
  const Shaded gpu = shade({v}, VSGL_SHADE_GLOSSY, nullptr, 0.0f, nullptr, true);
  expectPointLight(
      gpu, position, 0.0,
      [&](glm::dvec3 toward) {
        return glm::dvec3(power) * std::max(glm::dot(glm::dvec3(normal), toward), 0.0) /
               3.141592653589793;
      },
      "VPL point-light limit");
}

// vsgl-math.md section 12, case 14: NaN and Inf in a host's material channels (a broken texture)
// must not become NaN light. Each poisoned pixel gets finite, non-negative light; a NaN albedo
// reads as black, so that pixel's diffuse light is 0; every other pixel is unchanged, bit for
// bit (the guard is per pixel and the pass is deterministic).
TEST_F(VsglShadeTest, NonFiniteMaterialGivesFiniteLight) {
  const std::vector<gpu::Vsgl> vsgls = hardCaseVsgls(scene_, receiver(kWidth / 2, kHeight / 2));
  const Shaded clean = shade(vsgls, VSGL_SHADE_GLOSSY);
  const std::vector<glm::uvec2> poisoned = {{12, 12}, {24, 16}, {34, 20}};
  for (const glm::uvec2& p : poisoned) ASSERT_FALSE(decoded_.at(p.x, p.y).background());
  using testing_gpu::kHalfInf;
  using testing_gpu::kHalfNan;
  pokeMaterials(*gbuffer_, {{false, poisoned[0], 0, 2, kHalfNan},  // albedo
                            {false, poisoned[1], 3, 3, kHalfNan},  // roughness
                            {true, poisoned[2], 0, 2, kHalfInf},   // F0
                            {false, poisoned[2], 3, 3, kHalfInf}});
  const Shaded dirty = shade(vsgls, VSGL_SHADE_GLOSSY);
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = size_t{y} * kWidth + x;
      const bool hit =
          std::find(poisoned.begin(), poisoned.end(), glm::uvec2(x, y)) != poisoned.end();
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(dirty.diffuse[i][c]) && std::isfinite(dirty.glossy[i][c]))
            << "pixel " << x << ", " << y;
        EXPECT_GE(dirty.diffuse[i][c], 0.0f);
        EXPECT_GE(dirty.glossy[i][c], 0.0f);
        if (!hit) {
          EXPECT_EQ(dirty.diffuse[i][c], clean.diffuse[i][c]) << "pixel " << x << ", " << y;
          EXPECT_EQ(dirty.glossy[i][c], clean.glossy[i][c]) << "pixel " << x << ", " << y;
        }
      }
    }
  const size_t black = size_t{poisoned[0].y} * kWidth + poisoned[0].x;
  EXPECT_EQ(glm::vec3(dirty.diffuse[black]), glm::vec3(0.0f));
}

}  // namespace

// VSGL culling (VSGL_SHADE_CULL) against the same shading without it, with the hard-case VSGLs
// and 64 faint ones around the box: every pixel keeps all but at most tau of its light, in
// each channel relative to its largest channel, because the skipped VSGLs' bounds add up to at
// most tau of the least light in the subgroup (the bound is conservative:
// tests/unit/test_vsgl_bound.cpp). Slack: 1e-5 of the pixel's light for the fp32 sum, whose terms
// changed. Culling never adds light (the same slack). At tau = 0.2 something must be skipped,
// or the test would prove nothing; the counts add up to one test per VSGL per subgroup with a
// surface pixel, and full-rate shading counts at level 0.
TEST_F(VsglShadeTest, CullingLosesAtMostItsBudget) {
  std::vector<gpu::Vsgl> vsgls = hardCaseVsgls(scene_, receiver(kWidth / 2, kHeight / 2));
  const engine::Bounds b = scene_.bounds();
  for (int i = 0; i < 64; ++i) {
    const float t = float(i) / 64.0f;
    const glm::vec3 mean =
        b.min + (b.max - b.min) * glm::vec3(0.1f + 0.8f * t, 0.5f + 0.4f * std::sin(9.0f * t),
                                            0.1f + 0.8f * std::fmod(7.0f * t, 1.0f));
    gpu::Vsgl v{};
    v.diffuse = vsglLobe(mean, 1e-3f, glm::vec3(std::sin(5.0f * t), -1.0f, std::cos(3.0f * t)),
                         2.2925f, glm::vec3(1e-3f));
    v.specular = vsglLobe(mean, 1e-3f, {0, 1, 0}, 30.0f, glm::vec3(5e-4f));
    vsgls.push_back(v);
  }
  const auto count = static_cast<uint32_t>(vsgls.size());
  size_t surface = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) surface += !decoded_.at(x, y).background();
  for (uint32_t flags :
       {VSGL_SHADE_GLOSSY | VSGL_SHADE_VISIBILITY | VSGL_SHADE_PLANAR, VSGL_SHADE_VISIBILITY}) {
    const Shaded full = shade(vsgls, flags);
    for (float budget : {0.01f, 0.2f}) {
      SCOPED_TRACE("flags " + std::to_string(flags) + ", budget " + std::to_string(budget));
      gpu::VsglShadeStats stats{};
      const Shaded culled = shade(vsgls, flags | VSGL_SHADE_CULL, nullptr, budget, &stats);
      double worst = 0.0;  // largest loss / (tau x light)
      for (size_t i = 0; i < full.diffuse.size(); ++i) {
        const glm::dvec3 want = glm::dvec3(full.diffuse[i]) + glm::dvec3(full.glossy[i]);
        const glm::dvec3 got = glm::dvec3(culled.diffuse[i]) + glm::dvec3(culled.glossy[i]);
        const double light = std::max({want.r, want.g, want.b});
        for (int c = 0; c < 3; ++c) {
          ASSERT_TRUE(std::isfinite(got[c])) << "pixel " << i;
          const double loss = want[c] - got[c];
          EXPECT_GE(loss, -1e-5 * light) << "pixel " << i << " channel " << c;
          EXPECT_LE(loss, (budget + 1e-5) * light) << "pixel " << i << " channel " << c;
          if (light > 0.0) worst = std::max(worst, loss / (budget * light));
        }
      }
      const uint32_t tested = stats.tested[0], skipped = stats.skipped[0];
      std::printf(
          "flags %u, budget %.2f: %u of %u subgroup x VSGL tests skipped; worst loss %.3f "
          "of the budget\n",
          flags, budget, skipped, tested, worst);
      EXPECT_EQ(tested % count, 0u);
      EXPECT_GT(tested, 0u);
      EXPECT_LE(tested, count * surface);
      EXPECT_LE(skipped, tested);
      for (int level = 1; level < 4; ++level) EXPECT_EQ(stats.tested[level], 0u);
      if (budget > 0.1f) {
        EXPECT_GT(skipped, 0u);
      }
    }
  }
}
