// Conventions check between the GPU renderer and the CPU ground truth (issue 5): the GPU's
// direct light (shadow maps) against the path tracer's (exact shadow rays) on every built-in
// scene. Agreement proves that both use the same units, light falloff, BRDF and camera, which
// the indirect-light comparisons of the benchmark rely on.
#include <cstdio>
#include <string>

#include "embree_scene.h"
#include "engine/builtin_scenes.h"
#include "engine/gbuffer_reference.h"
#include "engine/image_metrics.h"
#include "gpu_fixture.h"
#include "path_tracer.h"

namespace {

constexpr uint32_t kWidth = 128, kHeight = 72;

// Pixels where both renderers shade the same surface: the path tracer's material at its hit
// (bilinear textures on mip 0) equals the GPU's decoded G-buffer (trilinear, mip-mapped) up to
// the fp16 storage. Texture filtering differs where a texture changes within a pixel's
// footprint (the checker's tiles alternate roughness 0.08 and 0.9, so one pixel may shade a
// mirror-like highlight on one side and a matte tile on the other): those pixels compare
// filters, not conventions, and are excluded (counted, and bounded by the test).
std::vector<engine::PixelClass> sameSurface(const engine::Scene& scene,
                                            const truth::EmbreeScene& rays,
                                            const engine::View& view,
                                            const testing_gpu::DirectFrame& gpu) {
  std::vector<engine::PixelClass> classes(size_t{view.width} * view.height,
                                          engine::PixelClass::Excluded);
  for (uint32_t y = 0; y < view.height; ++y)
    for (uint32_t x = 0; x < view.width; ++x) {
      const engine::CameraRay ray = engine::cameraRayReference(view, glm::dvec2(x + 0.5, y + 0.5));
      const truth::RayHit hit = rays.intersect(ray.origin, ray.dir);
      const size_t i = size_t{y} * view.width + x;
      const engine::GBufferSample& g = gpu.gbuffer.samples[i];
      if (!hit.hit || g.background()) {
        if (!hit.hit && g.background()) classes[i] = engine::PixelClass::Diffuse;
        continue;
      }
      const engine::GBufferSample s =
          engine::surfaceAt(scene, hit.triangle, hit.barycentrics, ray.dir);
      // fp16 storage: 2^-11 relative, below 2e-3 for values up to 1.
      if (std::abs(s.roughness - g.roughness) < 2e-3 && glm::length(s.diffuse - g.diffuse) < 2e-3 &&
          glm::length(s.f0 - g.f0) < 2e-3)
        classes[i] = engine::PixelClass::Diffuse;
    }
  return classes;
}

class ReferenceConventions : public testing_gpu::GpuTest,
                             public ::testing::WithParamInterface<std::string> {};

// The GPU's direct light against the path tracer's, RMSE over the image relative to the
// reference's mean. Without shadows on either side the two compute the same thing from
// different code (rasterizer + G-buffer + fp32 shader against Embree + double), so the
// difference must stay within the 1 %; with shadows, the GPU's shadow maps (1024^2,
// 3x3 PCF, normal offset) differ from exact shadow rays along every shadow edge and in thin
// occluders: printed, not bounded, since it measures the shadow maps, not the conventions.
TEST_P(ReferenceConventions, GpuDirectLightMatchesPathTracer) {
  const engine::Scene scene = engine::makeBuiltinScene(GetParam());
  const engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
  const truth::EmbreeScene rays(scene);
  uint32_t light = 0;
  while (scene.lights[light].type == engine::LightType::Point) ++light;
  for (bool shadows : {false, true}) {
    const testing_gpu::DirectFrame gpu = renderDirect(scene, view, {1024, shadows});
    truth::PathTraceSettings settings;
    settings.minSamples = settings.maxSamples = 2;  // the direct light has no noise
    settings.directShadows = shadows;
    const truth::PathTraceImage traced = truth::pathTrace(scene, rays, view, light, settings);
    std::vector<glm::dvec3> gpuRadiance;
    for (const glm::vec4& c : gpu.radiance) gpuRadiance.emplace_back(c);
    const engine::ErrorMetrics m =
        engine::compareImages(gpuRadiance, traced.direct, sameSurface(scene, rays, view, gpu));
    const double relative = m.rmse / m.referenceMean;
    std::printf(
        "%s, shadows %s: direct-light RMSE %.4g W/(sr m^2), %.3f %% of the mean %.4g "
        "(%zu of %u pixels with the same surface on both sides)\n",
        GetParam().c_str(), shadows ? "on" : "off", m.rmse, 100.0 * relative, m.referenceMean,
        m.pixels, kWidth * kHeight);
    EXPECT_EQ(m.nonFinite, 0u);
    // Texture-filter disagreements are a thin set of pixels along texture edges.
    EXPECT_GT(m.pixels, size_t{kWidth} * kHeight * 9 / 10);
    if (!shadows) {
      EXPECT_LT(relative, 0.01);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, ReferenceConventions,
                         ::testing::Values("cornell", "atrium", "checker"));

}  // namespace
