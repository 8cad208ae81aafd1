// The reflective shadow map: texel solid angles, GPU flux pass against its double-precision
// twin, zero power off the cone and on background, and conservation of the light's flux.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "engine/builtin_scenes.h"
#include "engine/gbuffer_reference.h"
#include "engine/gltf.h"
#include "gpu_fixture.h"
#include "passes/rsm.h"
#include "reference/rsm_reference.h"
#include "rsm_rig.h"

namespace {

// The midpoint sum of A cos^3(theta) over the texels converges to the frustum's exact solid angle
// 4 asin(sin^2 h) at second order: measured relative errors 2.0e-4, 5.1e-5, 1.3e-5 at 32, 64 and
// 128 texels for h = 0.6 (error ~ 0.21 / n^2).
TEST(RsmSolidAngle, TexelSolidAnglesSumToTheFrustum) {
  const double h = 0.6, exact = gi::frustumSolidAngle(h);
  double previous = 0.0;
  for (uint32_t n : {32u, 64u, 128u}) {
    double error = std::abs(gi::rsmSolidAngleSum(n, h) - exact) / exact;
    EXPECT_LT(error, 0.25 / (double(n) * n)) << n << " texels";
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 3.8) << "second-order convergence";
      EXPECT_LT(previous / error, 4.2) << "second-order convergence";
    }
    previous = error;
  }
}

struct GpuRsm {
  engine::GBufferData surface;
  std::vector<glm::vec4> position, diffuse, specular;
};

GpuRsm renderRsm(engine::Context& ctx, const engine::Scene& scene, const engine::Light& light,
                 const gi::RsmView& view, uint32_t size) {
  engine::SceneGpu gpuScene = engine::uploadScene(ctx, scene);
  engine::Rasterizer rasterizer(ctx);
  engine::GBufferResolve resolve(ctx);
  gi::ReflectiveShadowMap rsm(ctx, size);
  ctx.submitAndWait(
      [&](VkCommandBuffer cmd) { rsm.record(cmd, gpuScene, rasterizer, resolve, view, light); });
  return {engine::readbackGBuffer(ctx, rsm.surface()), rsm.position().readbackRgba32f(ctx),
          rsm.diffuseFlux().readbackRgba32f(ctx), rsm.specularFlux().readbackRgba32f(ctx)};
}

double maxLuminance(const std::vector<gi::RsmTexelReference>& ref) {
  double m = 0.0;
  for (const auto& t : ref) m = std::max(m, t.incident.g);
  return m;
}

// The GPU flux pass against rsmFluxReference on the GPU's own light G-buffer (tolerances in
// FluxMatchesReferenceOnBuiltinScenes).
void expectFluxMatchesReference(const GpuRsm& gpu, const gi::RsmView& view,
                                const engine::Light& light) {
  const auto ref = gi::rsmFluxReference(gpu.surface, view, gi::lightFluxSource(light));
  const double floor = 1e-6 * maxLuminance(ref);
  // A spot's falloff f = clamp(s cos(theta) - s cos(outer), 0, 1) magnifies the fp32 error of
  // cos(theta) (a few ulps, 8 allowed) by s / f in f and twice that in f^2: with the lounge's
  // narrow cones (s = 18) that is 1.7e-5 at f = 0.33.
  const double scale = light.type == engine::LightType::Spot
                           ? 1.0 / std::max(std::cos(double(light.innerConeAngle)) -
                                                std::cos(double(light.outerConeAngle)),
                                            1e-4)
                           : 0.0;
  size_t lit = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    const auto& r = ref[i];
    double relative = 1e-5;
    if (scale > 0.0 && glm::length(r.offset) > 0.0) {
      const double c = glm::dot(glm::normalize(r.offset), glm::dvec3(view.axis));
      const double f = std::clamp(scale * (c - std::cos(double(light.outerConeAngle))), 0.0, 1.0);
      relative += 2.0 * 8.0 * 0x1p-24 * scale * c / std::max(f, 1e-3);
    }
    auto near = [&](double g, double c, double abs) {
      return std::abs(g - c) <= relative * std::abs(c) + abs;
    };
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(near(gpu.diffuse[i][k], r.diffuseFlux[k], floor))
          << "texel " << i << " diffuse " << k;
      ASSERT_TRUE(near(gpu.specular[i][k], r.specularFlux[k], floor))
          << "texel " << i << " specular " << k;
    }
    if (r.lit != gpu.position[i].w) {
      // Only a texel whose power is at the rounding floor may switch between lit and unlit.
      ASSERT_LE(r.incident.g, floor) << "texel " << i;
      continue;
    }
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(near(gpu.position[i][k], r.offset[k], 1e-6))
          << "texel " << i << " position " << k;
    lit += r.lit > 0.0;
  }
  EXPECT_GT(lit, ref.size() / 4) << "the light should reach much of its RSM";
}

class Rsm : public testing_gpu::GpuTest {};

TEST_F(Rsm, FluxMatchesReferenceOnBuiltinScenes) {
  // fp32 against double from identical inputs: the unprojection and cos^3 falloff are a few
  // dozen roundings (relative 1e-5 covers them with margin); near the cone's rim the falloff
  // goes to 0 and its relative error is unbounded, hence the absolute floor of 1e-6 of the
  // brightest texel. Positions: relative 1e-5 of the offset plus 1e-6 m. Every view of every
  // light of every built-in scene (the lounge's point light has six).
  const uint32_t size = 64;
  for (const std::string& name : engine::builtinSceneNames()) {
    const engine::Scene scene = engine::makeBuiltinScene(name);
    for (const engine::Light& light : scene.lights) {
      const std::vector<gi::RsmView> views = gi::makeRsmViews(scene.bounds(), light, size);
      for (size_t v = 0; v < views.size(); ++v) {
        SCOPED_TRACE(name + ", " + light.name + ", view " + std::to_string(v));
        expectFluxMatchesReference(renderRsm(ctx(), scene, light, views[v], size), views[v], light);
      }
    }
  }
}

// alpha_mask.gltf: a spot 2 m above a screen whose 1 m checker cells alternate opaque and cut
// out (alphaMode MASK), a green floor 1 m below it. The RSM sees the floor exactly through the
// holes: each texel whose ray meets the screen plane in a cut cell shows the floor's green, every
// other one the screen's grey (texels whose ray passes within 4 mm of a cell edge, under a
// quarter of a texel there, are not judged: the GPU interpolates the coordinates in fp32).
// Without the cut-outs the screen hides the floor from every texel.
TEST_F(Rsm, AlphaMaskCutsTheLightsView) {
  const uint32_t size = 128;
  for (const bool cut : {true, false}) {
    SCOPED_TRACE(cut ? "MASK" : "OPAQUE");
    engine::Scene scene = engine::loadGltf(std::string(VSGL_TEST_DATA) + "/gltf/alpha_mask.gltf");
    if (!cut) scene.materials[1].alphaCutoff = 0.0f;
    testing_gpu::RsmRig rig(ctx(), scene, size);
    const engine::GBufferData g = engine::readbackGBuffer(ctx(), rig.rsm->surface());
    size_t judged = 0, floorSeen = 0;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const engine::CameraRay ray =
            engine::cameraRayReference(rig.view.view, glm::dvec2(x + 0.5, y + 0.5));
        const glm::dvec3 onScreen = ray.origin + ray.dir * ((1.0 - ray.origin.y) / ray.dir.y);
        const glm::dvec2 cell = (glm::dvec2(onScreen.x, onScreen.z) + 2.0);  // 1 m cells
        const glm::dvec2 edge = glm::abs(cell - glm::round(cell));
        if (std::min(edge.x, edge.y) < 0.004) continue;
        const bool hole = (static_cast<int>(cell.x) + static_cast<int>(cell.y)) % 2 == 1;
        const engine::GBufferSample& s = g.samples[size_t{y} * size + x];
        ASSERT_FALSE(s.background()) << "texel " << x << ", " << y;
        const bool green = s.diffuse.g > 2.0 * s.diffuse.r;
        EXPECT_EQ(green, cut && hole) << "texel " << x << ", " << y;
        ++judged;
        floorSeen += green;
      }
    EXPECT_GT(judged, size_t{size} * size * 9 / 10);
    if (cut) {
      EXPECT_GT(floorSeen, judged / 3);
      EXPECT_LT(floorSeen, judged * 2 / 3);
    }
  }
}

TEST_F(Rsm, BackgroundAndTexelsOutsideTheConeCarryNoPower) {
  engine::Scene scene = engine::makeBuiltinScene("cornell");
  const engine::Light& light = scene.lights.at(0);
  const uint32_t size = 64;
  gi::RsmView view = gi::makeRsmView(scene, light, size);
  GpuRsm gpu = renderRsm(ctx(), scene, light, view, size);
  const double cosOuter = std::cos(light.outerConeAngle);
  size_t outside = 0;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      size_t i = size_t{y} * size + x;
      double u = ((x + 0.5) / size * 2.0 - 1.0) * view.tanHalfAngle;
      double v = ((y + 0.5) / size * 2.0 - 1.0) * view.tanHalfAngle;
      bool offCone = 1.0 / std::sqrt(1.0 + u * u + v * v) < cosOuter - 1e-4;
      if (!offCone && !gpu.surface.samples[i].background()) continue;
      ++outside;
      EXPECT_EQ(gpu.position[i], glm::vec4(0.0f)) << "texel " << x << ", " << y;
      EXPECT_EQ(gpu.diffuse[i], glm::vec4(0.0f)) << "texel " << x << ", " << y;
      EXPECT_EQ(gpu.specular[i], glm::vec4(0.0f)) << "texel " << x << ", " << y;
    }
  }
  EXPECT_GT(outside, size_t{size}) << "the square frustum's corners lie outside the cone";
}

TEST_F(Rsm, IncidentFluxEqualsIntensityTimesTheConesWeightedSolidAngle) {
  // A spot inside a closed room: every frustum ray hits a wall, so the RSM must capture
  // I * integral of falloff over the sphere = I * 2 pi * int falloff(cos t) sin t dt. The falloff
  // is continuous, so the texel sum converges at second order like the solid angle (measured
  // relative error printed; 1e-3 at 128^2 leaves a wide margin over that rate).
  engine::Scene room = engine::makeBuiltinScene("cornell");
  engine::Light spot = room.lights.at(0);
  spot.intensity = 1.0f;
  spot.color = glm::vec3(1.0f);
  spot.position = glm::vec3(0.0f, 1.0f, 0.0f);  // mid-room: the open front is behind it
  spot.direction = glm::vec3(0.0f, -0.2f, -1.0f);
  spot.direction = glm::normalize(spot.direction);
  spot.innerConeAngle = 0.3f;
  spot.outerConeAngle = 0.6f;
  const uint32_t size = 128;
  gi::RsmView view = gi::makeRsmView(room, spot, size);
  GpuRsm gpu = renderRsm(ctx(), room, spot, view, size);
  double total = 0.0;
  size_t background = 0;
  for (size_t i = 0; i < gpu.diffuse.size(); ++i) {
    total += gpu.diffuse[i].a;  // luminance of Phi_in; white light of unit intensity
    background += gpu.surface.samples[i].background();
  }
  ASSERT_EQ(background, 0u) << "the spot must see walls in every direction";
  const glm::dvec2 f(engine::spotFalloff(spot));
  double expected = 0.0;
  const int steps = 200000;
  for (int k = 0; k < steps; ++k) {
    double t = (k + 0.5) / steps * spot.outerConeAngle;
    double a = std::clamp(std::cos(t) * f.x + f.y, 0.0, 1.0);
    expected += a * a * std::sin(t);
  }
  expected *= 2.0 * M_PI * spot.outerConeAngle / steps;
  double error = std::abs(total - expected) / expected;
  std::printf("RSM incident flux %.8f W, expected %.8f W, relative error %.2e\n", total, expected,
              error);
  EXPECT_LT(error, 1e-3);
}

// A spot's range (KHR_lights_punctual) scales its RSM flux by the window of its direct light,
// clamp(1 - (d / range)^4, 0, 1) at the texel's distance d: the GPU against the twin (same
// tolerances as above, plus 5e-5 of the unwindowed flux: the window 1 - r^4 moves by 4 r^4 times
// the distance's relative error, and the GPU's positions agree with the twin's to 1e-5 relative
// (FluxMatchesReferenceOnBuiltinScenes), so its relative error is unbounded where it nears 0), and
// the twin with the range against the twin without it, texel by texel (relative 1e-12: the same
// double arithmetic times the window).
TEST_F(Rsm, RangeWindowScalesTheFluxAsTheDirectLight) {
  engine::Scene scene = engine::makeBuiltinScene("cornell");
  engine::Light light = scene.lights.at(0);
  light.range = 2.2f;  // the spot is 1.9 m above the floor: the far floor lies past the range
  const uint32_t size = 64;
  gi::RsmView view = gi::makeRsmView(scene, light, size);
  GpuRsm gpu = renderRsm(ctx(), scene, light, view, size);
  const auto ref = gi::rsmFluxReference(gpu.surface, view, gi::lightFluxSource(light));
  engine::Light unbounded = light;
  unbounded.range = 0.0f;
  const auto full = gi::rsmFluxReference(gpu.surface, view, gi::lightFluxSource(unbounded));
  const double floor = 1e-6 * maxLuminance(full);
  size_t cut = 0, windowed = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    if (full[i].lit == 0.0) continue;
    const double r = glm::length(full[i].offset) / light.range;
    const double window = std::clamp(1.0 - r * r * r * r, 0.0, 1.0);
    cut += window == 0.0;
    windowed += window > 0.0 && window < 0.9;
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(ref[i].diffuseFlux[k], window * full[i].diffuseFlux[k],
                  1e-12 * full[i].diffuseFlux[k])
          << "texel " << i;
      ASSERT_LE(std::abs(gpu.diffuse[i][k] - ref[i].diffuseFlux[k]),
                1e-5 * ref[i].diffuseFlux[k] + 5e-5 * full[i].diffuseFlux[k] + floor)
          << "texel " << i << " diffuse " << k;
      ASSERT_LE(std::abs(gpu.specular[i][k] - ref[i].specularFlux[k]),
                1e-5 * ref[i].specularFlux[k] + 5e-5 * full[i].specularFlux[k] + floor)
          << "texel " << i << " specular " << k;
    }
    if (window == 0.0) {
      EXPECT_EQ(gpu.position[i].w, 0.0f) << "texel " << i << " past the range";
    }
  }
  EXPECT_GT(cut, ref.size() / 20) << "some of the room must lie past the range";
  EXPECT_GT(windowed, ref.size() / 20) << "some of it inside the window's fall-off";
}

// A point light's six cube faces (docs/techniques/point-lights.md) tile the sphere of
// directions: every direction falls inside exactly one face's frustum (10^5 random directions;
// none lands on an edge), and the faces' texel solid angles add up to 4 pi at the same second
// order as one frustum's (TexelSolidAnglesSumToTheFrustum: 6 x 1.3e-5 relative at 128 texels).
TEST(RsmView, PointLightFacesTileTheSphere) {
  engine::Scene scene = engine::makeBuiltinScene("cornell");
  engine::Light light = scene.lights.at(0);
  light.type = engine::LightType::Point;
  const uint32_t size = 128;
  const std::vector<gi::RsmView> faces = gi::makeRsmViews(scene.bounds(), light, size);
  ASSERT_EQ(faces.size(), gi::kCubeFaces);
  double solidAngle = 0.0;
  for (const gi::RsmView& f : faces) {
    EXPECT_TRUE(f.perspective);
    EXPECT_FLOAT_EQ(f.tanHalfAngle, 1.0f);
    EXPECT_EQ(f.origin, light.position);
    solidAngle += gi::rsmSolidAngleSum(size, 0.25 * M_PI);
  }
  EXPECT_NEAR(solidAngle, 4.0 * M_PI, 4.0 * M_PI * 6.0 * 0.25 / (double(size) * size));
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 100000; ++i) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
    int inside = 0;
    for (const gi::RsmView& f : faces) {
      const glm::dvec4 clip = glm::dmat4(f.raster.matrix) * glm::dvec4(d, 1.0);
      inside += clip.w > 0.0 && std::abs(clip.x) < clip.w && std::abs(clip.y) < clip.w;
    }
    ASSERT_EQ(inside, 1) << "direction " << d.x << ", " << d.y << ", " << d.z;
  }
}

// Each face of a point light's RSM is a spot's RSM without a cone: the GPU against the twin on
// every face, with the tolerances of FluxMatchesReferenceOnBuiltinScenes, a light in the middle
// of the Cornell box (every face sees walls; the open front's face sees little).
TEST_F(Rsm, PointLightFacesMatchTheReference) {
  engine::Scene scene = engine::makeBuiltinScene("cornell");
  engine::Light light = scene.lights.at(0);
  light.type = engine::LightType::Point;
  light.position = glm::vec3(0.0f, 1.0f, 0.0f);
  const uint32_t size = 64;
  size_t lit = 0;
  for (const gi::RsmView& view : gi::makeRsmViews(scene.bounds(), light, size)) {
    GpuRsm gpu = renderRsm(ctx(), scene, light, view, size);
    const auto ref = gi::rsmFluxReference(gpu.surface, view, gi::lightFluxSource(light));
    const double floor = 1e-6 * maxLuminance(ref);
    for (size_t i = 0; i < ref.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_LE(std::abs(gpu.diffuse[i][k] - ref[i].diffuseFlux[k]),
                  1e-5 * ref[i].diffuseFlux[k] + floor)
            << "texel " << i;
        ASSERT_LE(std::abs(gpu.specular[i][k] - ref[i].specularFlux[k]),
                  1e-5 * ref[i].specularFlux[k] + floor)
            << "texel " << i;
      }
      lit += ref[i].lit > 0.0;
    }
  }
  EXPECT_GT(lit, 4u * size * size) << "most of the six faces see the room";
}

TEST(RsmView, RefusesPointLightsAndOverwideSpots) {
  engine::Scene scene = engine::makeBuiltinScene("cornell");
  engine::Light light = scene.lights.at(0);
  light.type = engine::LightType::Point;
  EXPECT_THROW(gi::makeRsmView(scene, light, 64), engine::Error);
  light.type = engine::LightType::Spot;
  light.outerConeAngle = 1.5f;
  EXPECT_THROW(gi::makeRsmView(scene, light, 64), engine::Error);
}

}  // namespace
