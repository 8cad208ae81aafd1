// Adaptive shading (passes/adaptive_shading.cpp, adaptive_decide.comp and vsgl_shade.comp's
// queue variant) against its double twin (reference/adaptive_reference.cpp), level by level on
// a real G-buffer: the same texels are queued, the queued ones shade like the CPU shading
// reference, and the others interpolate their parents as the twin does. With the coarsest level
// at 0 the pass must reproduce full-rate shading bit for bit.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "engine/builtin_scenes.h"
#include "engine/commands.h"
#include "gpu_fixture.h"
#include "passes/adaptive_shading.h"
#include "passes/ism.h"
#include "reference/adaptive_reference.h"
#include "test_vsgls.h"

namespace {

// Not multiples of 8: the levels' last texels are clamped at the borders.
constexpr uint32_t kWidth = 61, kHeight = 37;

using testing_gpu::vsglLobe;

class AdaptiveShadingTest : public testing_gpu::GpuTest {
 protected:
  void SetUp() override {
    testing_gpu::GpuTest::SetUp();
    if (IsSkipped()) return;
    scene_ = engine::makeBuiltinScene("cornell");
    // The white walls and boxes without a specular lobe (KHR_materials_specular strength 0):
    // their texels go to the plain queue.
    for (engine::Material& m : scene_.materials)
      if (m.name == "white") m.specularFactor = 0.0f;
    // 0.5 m back from the scene's camera: the box's outline against the sky is in view.
    engine::Camera camera = scene_.cameras.at(0);
    camera.cameraToWorld[3] += camera.cameraToWorld[2] * 0.5f;
    view_ = engine::cameraView(camera, kWidth, kHeight);
    gpuScene_ = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx(), scene_));
    gbuffer_ = std::make_unique<engine::GBuffer>(renderGBuffer(*gpuScene_, view_));
    decoded_ = engine::readbackGBuffer(ctx(), *gbuffer_);
    // Ordinary lobes in the box, some near the walls (light that changes fast) and some in
    // the middle (light that changes slowly).
    const engine::Bounds b = scene_.bounds();
    const glm::vec3 centre = 0.5f * (b.min + b.max), extent = b.max - b.min;
    for (int i = 0; i < 10; ++i) {
      const float t = float(i) / 10.0f, fi = float(i);
      const glm::vec3 mean =
          centre + extent * glm::vec3(0.3f * std::cos(6.28f * t), 0.4f * (t - 0.5f),
                                      0.3f * std::sin(6.28f * t));
      const glm::vec3 axis(std::sin(2.4f * fi), std::cos(1.7f * fi), std::sin(0.9f * fi + 1.0f));
      gpu::Vsgl v{};
      v.diffuse =
          vsglLobe(mean, 2e-2f * float(1 + i % 3), axis, 2.2925f, glm::vec3(1.0f, 0.7f, 0.4f));
      v.specular = vsglLobe(mean, 1e-2f, -axis, 20.0f, glm::vec3(0.3f, 0.5f, 1.0f));
      vsgls_.push_back(v);
    }
  }

  // The pass's outputs, as the twin's levels: [L] is level L (0 = the module's outputs).
  struct Run {
    std::vector<gi::AdaptiveLevel> levels;
    std::vector<std::set<uint32_t>> queues;  // packed texels per level, both queues
    std::vector<std::set<uint32_t>> plain;   // of those, the plain queue's
    std::vector<gpu::AdaptiveQueueHeader> heads;
    gi::ShadingCounts counts;
    std::vector<float> levelMap;  // per pixel: the level its light was shaded at, -1 sky
    uint32_t padding = 0;         // empty entries of ordered queues, every level
  };

  // `ordered`: with VSGL culling (budget 0, which skips only VSGLs whose bound is 0), so that the
  // decision pass appends its queues in order, padded (AdaptiveDecidePush::orderedAlign).
  Run run(const gi::AdaptiveSettings& settings, bool splitGlossy = true, bool ordered = false) {
    engine::Buffer buffer(ctx(), vsgls_.size() * sizeof(gpu::Vsgl),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::Upload);
    buffer.upload(ctx(), std::span<const gpu::Vsgl>(vsgls_));
    gi::Ism ism(ctx(), {32, 1u << 12, 256}, uint32_t(vsgls_.size()));  // bound, never read
    gi::VsglShade shade(ctx());
    gi::AdaptiveShading pass(ctx(), kWidth, kHeight);
    gi::IndirectImages out = gi::createIndirectImages(ctx(), kWidth, kHeight);
    gi::VsglShade::Inputs in{&buffer, uint32_t(vsgls_.size()), VSGL_SHADE_GLOSSY, &ism.atlas(),
                             ism.params()};
    if (ordered) in.flags |= VSGL_SHADE_CULL;
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      pass.record(cmd, *gbuffer_, view_, in, settings, splitGlossy, shade, out);
    });
    Run r;
    r.counts = pass.lastCounts();
    const std::vector<std::byte> map = pass.levelMap().readback(ctx());
    r.levelMap.resize(map.size() / sizeof(float));
    std::memcpy(r.levelMap.data(), map.data(), map.size());
    for (uint32_t level = 0; level <= settings.coarsestLevel; ++level) {
      gi::IndirectImages& images = level == 0 ? out : pass.levelImages(level);
      const std::vector<glm::vec4> d = images.diffuse.readbackRgba32f(ctx());
      const std::vector<glm::vec4> g = images.glossy.readbackRgba32f(ctx());
      gi::AdaptiveLevel l;
      l.width = gpu::adaptiveLevelSize(kWidth, level);
      l.height = gpu::adaptiveLevelSize(kHeight, level);
      for (size_t i = 0; i < d.size(); ++i) {
        l.diffuse.emplace_back(d[i]);
        l.glossy.emplace_back(g[i]);
        l.origin.push_back(level == 0 ? 0u : uint32_t(d[i].a));
        l.exact.push_back(level > 0 && g[i].a == 1.0f);
      }
      r.levels.push_back(std::move(l));
      r.queues.emplace_back();
      r.plain.emplace_back();
      for (bool plain : {false, true}) {
        const std::vector<uint32_t> words = pass.queue(level, plain).readbackAs<uint32_t>(ctx());
        gpu::AdaptiveQueueHeader head;
        std::memcpy(&head, words.data(), sizeof(head));
        const size_t first = sizeof(head) / 4;
        std::set<uint32_t> texels(words.begin() + first, words.begin() + first + head.entries);
        texels.erase(ADAPTIVE_QUEUE_EMPTY);  // an ordered queue's padding
        EXPECT_EQ(texels.size(), head.shaded) << "a texel queued twice";
        r.padding += head.entries - head.shaded;
        EXPECT_EQ(head.groupsX, (head.entries + ADAPTIVE_QUEUE_GROUP - 1) / ADAPTIVE_QUEUE_GROUP);
        r.queues.back().insert(texels.begin(), texels.end());
        if (plain) {
          r.plain.back() = texels;
          r.heads.back().shaded += head.shaded;  // the glossy head counts the rest
        } else {
          r.heads.push_back(head);
        }
      }
    }
    return r;
  }

  // The CPU shading reference at a pixel, diffuse without the albedo (the levels' form).
  gi::IndirectRadiance shadeAt(glm::uvec2 pixel) const {
    const engine::GBufferSample& s = decoded_.at(pixel.x, pixel.y);
    const engine::CameraRay ray = engine::cameraRayReference(view_, glm::dvec2(pixel) + 0.5);
    const glm::dmat4 inv(view_.invViewProj);
    const glm::dvec2 ndc = (glm::dvec2(pixel) + 0.5) / glm::dvec2(kWidth, kHeight) * 2.0 - 1.0;
    const glm::dvec4 h = inv * glm::dvec4(ndc, s.depth, 1.0);
    gi::ShadeReceiver r;
    r.position = glm::dvec3(h) / h.w;
    r.view = -ray.dir;
    r.normal = s.normal;
    r.albedo = glm::dvec3(1.0);
    r.f0 = s.f0;
    r.f90 = s.f90;
    r.roughness = s.roughness;
    return gi::shadeReference(r, vsgls_, true, false);
  }

  engine::Scene scene_;
  engine::View view_;
  std::unique_ptr<engine::SceneGpu> gpuScene_;
  std::unique_ptr<engine::GBuffer> gbuffer_;
  engine::GBufferData decoded_;
  std::vector<gpu::Vsgl> vsgls_;
};

uint32_t pack(uint32_t x, uint32_t y) {
  return x | (y << ADAPTIVE_PACK_SHIFT);
}

// Level by level, the GPU's decisions against the twin's, given the GPU's own parents (so that
// each level is checked on its own). Tolerances:
// - Decisions: the twin rebuilds positions and decodes normals in double, the shader in fp32,
//   so a texel whose plane, normal or light test lands within rounding of its threshold may go
//   the other way: at most 1 % of a level's texels (and never where both agree on the sky).
// - Queued texels: the shading reference's tolerance (test_vsgl_shade.cpp, MatchesReference):
//   2e-3 of the value plus 1e-5 of the level's largest value.
// - Interpolated texels: the same four parent values and weights from integer pixel positions,
//   summed in fp32 against double: 1e-5 of the value plus 1e-7 of the largest.
TEST_F(AdaptiveShadingTest, LevelsMatchTheTwin) {
  for (const auto& [coarsest, ordered] : {std::pair{2u, false}, {3u, false}, {3u, true}}) {
    SCOPED_TRACE(ordered ? "ordered queues" : "queues in device order");
    gi::AdaptiveSettings settings;
    settings.coarsestLevel = coarsest;
    // These few VSGLs light the small image unevenly: a wider tolerance than the default
    // gives every level a mix of queued and interpolated texels.
    settings.lightTolerance = 0.5f;
    const Run gpu = run(settings, true, ordered);
    EXPECT_EQ(gpu.padding > 0, ordered) << gpu.padding << " empty queue entries";
    size_t interpolatedAtZero = 0, queuedAtZero = 0, sky = 0, interpolatedAbove = 0,
           plainQueued = 0;
    for (uint32_t level = coarsest + 1; level-- > 0;) {
      SCOPED_TRACE("coarsest " + std::to_string(coarsest) + ", level " + std::to_string(level));
      const gpu::AdaptiveDecidePush push =
          gi::adaptiveDecidePush(settings, view_, kWidth, kHeight, level, true);
      const gi::AdaptiveLevel twin = gi::adaptiveLevelReference(
          decoded_, push, level < coarsest ? &gpu.levels[level + 1] : nullptr,
          [&](glm::uvec2 pixel) { return shadeAt(pixel); });
      const gi::AdaptiveLevel& got = gpu.levels[level];
      const gpu::AdaptiveQueueHeader& head = gpu.heads[level];
      const size_t texels = size_t{twin.width} * twin.height;
      EXPECT_EQ(head.shaded + head.interpolated + head.reused + head.sky, texels);
      EXPECT_EQ(gpu.queues[level].size(), head.shaded) << "a texel in both queues";
      double largest = 0.0;
      for (size_t i = 0; i < texels; ++i)
        largest = std::max({largest, twin.diffuse[i].g, twin.glossy[i].b});
      ASSERT_GT(largest, 0.0);
      size_t disagree = 0, skyTexels = 0;
      for (uint32_t y = 0; y < twin.height; ++y)
        for (uint32_t x = 0; x < twin.width; ++x) {
          const size_t i = twin.index({x, y});
          const bool queued = gpu.queues[level].count(pack(x, y)) > 0;
          if (twin.sky[i]) {
            ++skyTexels;
            EXPECT_FALSE(queued) << "sky texel " << x << "," << y << " queued";
            EXPECT_EQ(got.diffuse[i], glm::dvec3(0.0));
            if (level == 0) {
              EXPECT_EQ(gpu.levelMap[i], -1.0f) << "level map at " << x << "," << y;
            }
            continue;
          }
          if (queued != bool(twin.queued[i])) {
            ++disagree;
            continue;
          }
          const double relative = queued ? 2e-3 : 1e-5, floor = queued ? 1e-5 : 1e-7;
          for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(got.diffuse[i][c], twin.diffuse[i][c],
                        relative * std::abs(twin.diffuse[i][c]) + floor * largest)
                << (queued ? "queued" : "interpolated") << " texel " << x << "," << y;
            EXPECT_NEAR(got.glossy[i][c], twin.glossy[i][c],
                        relative * std::abs(twin.glossy[i][c]) + floor * largest)
                << (queued ? "queued" : "interpolated") << " texel " << x << "," << y;
          }
          if (level > 0) {
            EXPECT_EQ(got.origin[i], twin.origin[i]) << "texel " << x << "," << y;
            EXPECT_EQ(got.exact[i], twin.exact[i]) << "texel " << x << "," << y;
          } else {
            EXPECT_EQ(gpu.levelMap[i], float(twin.origin[i])) << "level map at " << x << "," << y;
          }
        }
      EXPECT_EQ(skyTexels, head.sky);
      size_t plainDiffer = 0;
      for (uint32_t y = 0; y < twin.height; ++y)
        for (uint32_t x = 0; x < twin.width; ++x)
          plainDiffer += gpu.plain[level].count(pack(x, y)) != bool(twin.plain[twin.index({x, y})]);
      EXPECT_EQ(plainDiffer, 0u) << "the plain queue is chosen by the material alone";
      plainQueued += gpu.plain[level].size();
      std::printf(
          "coarsest %u level %u: %u queued (%zu without glossy), %u interpolated, %u reused, %u "
          "sky, %zu decisions differ\n",
          coarsest, level, head.shaded, gpu.plain[level].size(), head.interpolated, head.reused,
          head.sky, disagree);
      EXPECT_LE(disagree, texels / 100);
      if (level > 0) interpolatedAbove += head.interpolated;
      if (level == 0) {
        interpolatedAtZero = head.interpolated;
        queuedAtZero = head.shaded;
        sky = head.sky;
      }
    }
    // The case must exercise all three outcomes at full resolution, and interpolation above it.
    EXPECT_GT(interpolatedAbove, 0u);
    EXPECT_GT(plainQueued, 0u);
    EXPECT_LT(plainQueued, gpu.queues[0].size() + gpu.queues[1].size());
    EXPECT_GT(interpolatedAtZero, 0u);
    EXPECT_GT(queuedAtZero, 0u);
    EXPECT_GT(sky, 0u);
    // The counts the host reads back add up: every surface pixel's light came from one level.
    uint32_t fromLevels = 0;
    for (uint32_t n : gpu.counts.pixelsFrom) fromLevels += n;
    EXPECT_EQ(fromLevels + gpu.counts.skyPixels, kWidth * kHeight);
    EXPECT_EQ(gpu.counts.shaded[0], gpu.heads[0].shaded);
    // No pixel is shaded twice: the queues hold fewer texels than there are surface pixels.
    uint32_t shaded = 0;
    for (uint32_t n : gpu.counts.shaded) shaded += n;
    EXPECT_LT(shaded, kWidth * kHeight - gpu.counts.skyPixels);
  }
}

// Coarsest level 0: every surface pixel is queued at level 0 and shaded by the same code as the
// full-rate pass, so the images are identical bit for bit (without the glossy split, which the
// next test covers).
TEST_F(AdaptiveShadingTest, CoarsestLevelZeroIsFullShading) {
  gi::AdaptiveSettings settings;
  settings.coarsestLevel = 0;
  const Run adaptive = run(settings, false);
  engine::Buffer buffer(ctx(), vsgls_.size() * sizeof(gpu::Vsgl),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::Upload);
  buffer.upload(ctx(), std::span<const gpu::Vsgl>(vsgls_));
  gi::Ism ism(ctx(), {32, 1u << 12, 256}, uint32_t(vsgls_.size()));
  gi::VsglShade shade(ctx());
  gi::IndirectImages out = gi::createIndirectImages(ctx(), kWidth, kHeight);
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    shade.record(cmd, *gbuffer_, view_,
                 {&buffer, uint32_t(vsgls_.size()), VSGL_SHADE_GLOSSY, &ism.atlas(), ism.params()},
                 out);
  });
  const std::vector<glm::vec4> d = out.diffuse.readbackRgba32f(ctx());
  const std::vector<glm::vec4> g = out.glossy.readbackRgba32f(ctx());
  size_t lit = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(glm::dvec3(d[i]), adaptive.levels[0].diffuse[i]) << i;
    EXPECT_EQ(glm::dvec3(g[i]), adaptive.levels[0].glossy[i]) << i;
    lit += d[i].g > 0.0f;
  }
  EXPECT_GT(lit, d.size() / 2);
  EXPECT_EQ(adaptive.heads[0].shaded + adaptive.heads[0].sky, kWidth * kHeight);
}

}  // namespace

// The planner's "no glossy receiver" decision, per texel: texels whose F0 and F90 are 0 (the
// white surfaces here) are shaded by the variant without the glossy term. With it on and off the
// same texels are shaded and interpolated; the diffuse light is the same bit for bit, and so is
// the glossy light everywhere else. On those texels the full variant's glossy light is not
// exactly 0 (the SG fit's log floors leave ~1e-38), so it is bounded by 1e-6 of the pixel's
// light (the identity within 1e-6 relative); with the split it is exactly 0.
TEST_F(AdaptiveShadingTest, TexelsWithoutSpecularSkipTheGlossyTerm) {
  gi::AdaptiveSettings settings;
  const Run off = run(settings, false), on = run(settings, true);
  uint32_t plain = 0;
  for (uint32_t n : on.counts.shadedWithoutGlossy) plain += n;
  EXPECT_GT(plain, 0u);
  for (uint32_t n : off.counts.shadedWithoutGlossy) EXPECT_EQ(n, 0u);
  EXPECT_EQ(on.counts.shaded, off.counts.shaded);
  const gi::AdaptiveLevel &a = off.levels[0], &b = on.levels[0];
  size_t zeroed = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      const size_t i = a.index({x, y});
      EXPECT_EQ(b.diffuse[i], a.diffuse[i]) << x << "," << y;
      const engine::GBufferSample& s = decoded_.at(x, y);
      const bool specular = s.f0 != glm::dvec3(0.0) || s.f90 != 0.0;
      if (s.background() || specular) {
        EXPECT_EQ(b.glossy[i], a.glossy[i]) << x << "," << y;
        continue;
      }
      // A pixel without specular: its own glossy light, or light interpolated from texels
      // without specular (the F0 test keeps materials apart), is 0 with the split.
      EXPECT_EQ(b.glossy[i], glm::dvec3(0.0)) << x << "," << y;
      const double light = a.diffuse[i].r + a.diffuse[i].g + a.diffuse[i].b;
      for (int c = 0; c < 3; ++c) EXPECT_LE(a.glossy[i][c], 1e-6 * light) << x << "," << y;
      ++zeroed;
    }
  EXPECT_GT(zeroed, a.diffuse.size() / 10);
}

// vsgl-math.md section 12, case 14, through the pyramid: non-finite material channels at
// representative pixels of every level (and at an odd pixel, which level 0 alone reads) must
// not spread. Every test a NaN or Inf takes part in fails, so the texels around them are shaded
// rather than interpolated, and the shading reads such channels as 0 (albedo, F0) or 1
// (roughness). Every output is finite and non-negative, and a pixel with a NaN albedo gets no
// diffuse light.
TEST_F(AdaptiveShadingTest, NonFiniteMaterialStaysLocal) {
  const std::vector<glm::uvec2> poisoned = {{16, 16}, {24, 12}, {29, 19}};
  for (const glm::uvec2& p : poisoned) ASSERT_FALSE(decoded_.at(p.x, p.y).background());
  using testing_gpu::kHalfInf;
  using testing_gpu::kHalfNan;
  pokeMaterials(*gbuffer_, {{false, poisoned[0], 0, 2, kHalfNan},   // albedo, levels 0-3
                            {false, poisoned[1], 3, 3, kHalfNan},   // roughness, levels 0-2
                            {true, poisoned[2], 0, 2, kHalfInf}});  // F0, level 0 only
  gi::AdaptiveSettings settings;
  settings.coarsestLevel = 3;
  settings.lightTolerance = 0.5f;  // as in LevelsMatchTheTwin: interpolation happens
  const Run r = run(settings);
  EXPECT_GT(r.heads[0].interpolated, 0u);
  const gi::AdaptiveLevel& out = r.levels[0];
  for (size_t i = 0; i < out.diffuse.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(out.diffuse[i][c]) && std::isfinite(out.glossy[i][c])) << i;
      EXPECT_GE(out.diffuse[i][c], 0.0);
      EXPECT_GE(out.glossy[i][c], 0.0);
    }
  EXPECT_EQ(out.diffuse[out.index(poisoned[0])], glm::dvec3(0.0));
  // The NaN-albedo pixel reuses light shaded at a coarser level (its light test fails): the
  // path where the decision itself must read the albedo as 0.
  EXPECT_GT(r.levelMap[out.index(poisoned[0])], 0.0f);
  // Each poisoned pixel's light was shaded at that very pixel: it is a representative of the
  // level its light came from (no interpolation through the non-finite channel).
  for (const glm::uvec2& p : poisoned) {
    const float level = r.levelMap[out.index(p)];
    ASSERT_GE(level, 0.0f);
    const uint32_t step = 1u << uint32_t(level);
    EXPECT_TRUE(p.x % step == 0 && p.y % step == 0) << p.x << "," << p.y << " from level " << level;
  }
}
