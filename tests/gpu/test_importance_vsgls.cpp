// Importance VSGLs from the camera (BRSM stage A, vsgl-math.md section 7): the camera's
// G-buffer run through the RSM flux, attribute and generation passes as a unit-intensity spot
// without falloff. The image is not square and not a power of two, so it is padded into the
// pyramids; padding must carry neither power nor PDF.
#include <cmath>
#include <cstring>

#include "engine/builtin_scenes.h"
#include "gpu_fixture.h"
#include "passes/vsgl_generate.h"
#include "reference/rsm_reference.h"

namespace {

class ImportanceVsgls : public testing_gpu::GpuTest {};

TEST_F(ImportanceVsgls, CameraPixelsBecomeImportanceVsglsWithoutTouchingThePadding) {
  const uint32_t width = 96, height = 64, pyramidSize = 128;
  engine::Scene scene = engine::makeBuiltinScene("cornell");
  const engine::Camera& camera = scene.cameras.at(0);
  engine::View view = engine::cameraView(camera, width, height);
  gi::RsmView importance = gi::cameraImportanceView(view);

  engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
  engine::Rasterizer rasterizer(ctx());
  engine::GBufferResolve resolve(ctx());
  engine::GBuffer gbuffer = engine::createGBuffer(ctx(), width, height);
  engine::Buffer visibility(ctx(), engine::Rasterizer::visibilityBytes(width, height),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  gi::FluxPass flux(ctx());
  gi::VplImages vpls = gi::createVplImages(ctx(), width, height);
  gi::MipPyramid mips(ctx());
  gi::VsglAttributes attributes(ctx(), pyramidSize);
  gi::VsglGenerator generator(ctx(), 256);
  const gi::FluxSource unitImportance;  // radiance 1, no falloff
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, width, height});
    resolve.record(cmd, gpuScene, visibility, view, gbuffer);
    flux.record(cmd, gbuffer, importance, unitImportance, vpls);
    attributes.record(cmd, vpls, gbuffer, importance, mips);
    generator.record(cmd, attributes, importance, {256, 1.0f, VSGL_RULE_MODIFIED});
  });

  // Flux pass against its twin, as for light RSMs (tolerances of Rsm.FluxMatchesReference).
  engine::GBufferData surface = engine::readbackGBuffer(ctx(), gbuffer);
  auto ref = gi::rsmFluxReference(surface, importance, unitImportance);
  auto diffuse = vpls.diffuse.readbackRgba32f(ctx(), 0);
  double solidAngle = 0.0, largest = 0.0;
  for (const auto& t : ref) largest = std::max(largest, t.incident.g);
  for (size_t i = 0; i < ref.size(); ++i) {
    ASSERT_NEAR(diffuse[i].a, ref[i].incident.g, 1e-5 * ref[i].incident.g + 1e-6 * largest)
        << "pixel " << i;
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(diffuse[i][k], ref[i].diffuseFlux[k],
                  1e-5 * ref[i].diffuseFlux[k] + 1e-6 * largest)
          << "pixel " << i;
    solidAngle += diffuse[i].a;
  }
  // Every pixel sees the box, so the pixels' solid angles add up to the camera frustum's,
  // 4 asin(sin a sin b) for half angles a, b; the midpoint rule is second order (~1e-4 here).
  const double tanY = importance.tanHalfAngle, tanX = tanY * double(width) / height;
  const double frustum = 4.0 * std::asin(std::sin(std::atan(tanX)) * std::sin(std::atan(tanY)));
  std::printf("pixel solid angles %.6f sr, frustum %.6f sr\n", solidAngle, frustum);
  EXPECT_NEAR(solidAngle, frustum, 1e-3 * frustum);

  // Padding: zero everywhere outside the image in every level-0 attribute, also on a second
  // frame, which does not clear it again.
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    flux.record(cmd, gbuffer, importance, unitImportance, vpls);
    attributes.record(cmd, vpls, gbuffer, importance, mips);
  });
  for (int a = 0; a < VSGL_ATTR_COUNT; ++a) {
    auto base = attributes.pyramid(a).readbackRgba32f(ctx(), 0);
    for (uint32_t y = 0; y < pyramidSize; ++y)
      for (uint32_t x = 0; x < pyramidSize; ++x)
        if (x >= width || y >= height) {
          ASSERT_EQ(base[size_t{y} * pyramidSize + x], glm::vec4(0.0f))
              << "attribute " << a << " texel " << x << ", " << y;
        }
  }

  // Importance VSGLs: kernels centred inside the image, finite, and sharing the total
  // importance (modified FIS, within the 2 % of the energy test).
  auto v = generator.vsgls().readbackAs<gpu::Vsgl>(ctx());
  double total = 0.0, importanceSum = 0.0;
  for (uint32_t i = 0; i < 256; ++i) {
    EXPECT_LT(v[i].kernel.x * pyramidSize, float(width)) << "VSGL " << i;
    EXPECT_LT(v[i].kernel.y * pyramidSize, float(height)) << "VSGL " << i;
    EXPECT_TRUE(std::isfinite(v[i].diffuse.axisSharpness.w) &&
                std::isfinite(v[i].specular.axisSharpness.w));
    total += v[i].diffuse.power.g + v[i].specular.power.g;
  }
  for (const auto& t : ref) importanceSum += t.diffuseFlux.g + t.specularFlux.g;
  EXPECT_NEAR(total, importanceSum, 0.02 * importanceSum);
}

// The pyramids reduce only the source's region (MipPyramid's extent form) and keep the
// padding zero by clearing it when the extent changes; without specular lobes the specular
// pyramids are cleared once and left alone. Checked across a sequence that breaks either rule
// if its state were kept wrong: the glossy box padded, full size (which writes the padding),
// padded again (specular pyramids not zero), then the matte box padded twice without specular
// lobes (the first clears them, the second not) and once with them, and the glossy box again.
// After each frame the padding must be zero at every level, every level what a reduction of the
// whole image writes, to the bit, without specular lobes the specular pyramids zero, and the
// matte box's diffuse pyramids the same with and without them.
TEST_F(ImportanceVsgls, PyramidsStayExactAcrossExtentAndSpecularChanges) {
  const uint32_t pyramidSize = 128;
  const engine::Scene glossy = engine::makeBuiltinScene("cornell");
  const engine::Scene matte = [&] {
    engine::Scene scene = glossy;
    for (engine::Material& m : scene.materials) m.specularFactor = 0.0f;  // ws = 0
    return scene;
  }();
  engine::Rasterizer rasterizer(ctx());
  engine::GBufferResolve resolve(ctx());
  gi::FluxPass flux(ctx());
  gi::MipPyramid mips(ctx());
  gi::VsglAttributes attributes(ctx(), pyramidSize);
  struct Source {
    uint32_t width, height;
    engine::View view;
    engine::GBuffer gbuffer;
    gi::VplImages vpls;
  };
  // 0, 1: the glossy box padded and full size; 2: the matte box padded.
  std::vector<Source> sources;
  for (auto [scene, size] :
       {std::pair{&glossy, glm::uvec2(96, 64)}, std::pair{&glossy, glm::uvec2(pyramidSize)},
        std::pair{&matte, glm::uvec2(96, 64)}}) {
    engine::SceneGpu gpuScene = engine::uploadScene(ctx(), *scene);
    engine::View view = engine::cameraView(scene->cameras.at(0), size.x, size.y);
    Source source{size.x, size.y, view, engine::createGBuffer(ctx(), size.x, size.y),
                  gi::createVplImages(ctx(), size.x, size.y)};
    engine::Buffer visibility(ctx(), engine::Rasterizer::visibilityBytes(size.x, size.y),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, size.x, size.y});
      resolve.record(cmd, gpuScene, visibility, view, source.gbuffer);
      flux.record(cmd, source.gbuffer, gi::cameraImportanceView(view), gi::FluxSource{},
                  source.vpls);
    });
    sources.push_back(std::move(source));
  }
  auto levels = [&](int a) {
    std::vector<std::vector<glm::vec4>> l;
    for (uint32_t level = 0; pyramidSize >> level >= 1; ++level)
      l.push_back(attributes.pyramid(a).readbackRgba32f(ctx(), level));
    return l;
  };
  std::vector<std::vector<std::vector<glm::vec4>>> matteDiffuse;  // per attribute, level
  double glossyPower = 0.0;  // the glossy box's mean specular weight: the premise
  const struct {
    size_t source;
    bool specular;
  } frames[] = {{0, true}, {1, true}, {0, true}, {2, false}, {2, false}, {2, true}, {0, true}};
  for (size_t f = 0; f < std::size(frames); ++f) {
    Source& source = sources[frames[f].source];
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      attributes.record(cmd, source.vpls, source.gbuffer, gi::cameraImportanceView(source.view),
                        mips, nullptr, frames[f].specular);
    });
    for (int a = 0; a < VSGL_ATTR_COUNT; ++a) {
      const auto gpu = levels(a);
      for (size_t level = 0; level < gpu.size(); ++level) {
        const uint32_t size = pyramidSize >> level;
        const uint32_t w = (source.width + (1u << level) - 1) >> level;
        const uint32_t h = (source.height + (1u << level) - 1) >> level;
        for (uint32_t y = 0; y < size; ++y)
          for (uint32_t x = 0; x < size; ++x)
            if (x >= w || y >= h || (!frames[f].specular && a >= VSGL_ATTR_SPECULAR_POWER))
              ASSERT_EQ(gpu[level][size_t{y} * size + x], glm::vec4(0.0f))
                  << "frame " << f << " attribute " << a << " level " << level << " texel " << x
                  << ", " << y;
      }
      // The reduction of the whole image, in place, must change nothing.
      ctx().submitAndWait([&](VkCommandBuffer cmd) { mips.record(cmd, attributes.pyramid(a)); });
      ASSERT_EQ(levels(a), gpu) << "frame " << f << " attribute " << a;
      if (frames[f].source == 2 && a < VSGL_ATTR_SPECULAR_POWER) {
        if (matteDiffuse.size() < VSGL_ATTR_SPECULAR_POWER)
          matteDiffuse.push_back(gpu);
        else
          ASSERT_EQ(gpu, matteDiffuse[a]) << "frame " << f << " attribute " << a;
      }
      if (frames[f].source == 0 && a == VSGL_ATTR_SPECULAR_POWER)
        glossyPower = std::max(glossyPower, double(gpu.back()[0].a));
    }
  }
  ASSERT_GT(glossyPower, 0.0) << "the glossy box must fill the specular pyramids";
}

}  // namespace
