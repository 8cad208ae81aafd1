// The compute rasterizer against its CPU twin: identical coverage, triangle ids and depth bits
// (both evaluate the same IEEE-754 operations in the same order, without FMA contraction, so
// any difference is a bug rather than rounding), and watertightness of shared edges.
#include <cmath>
#include <cstring>
#include <random>

#include "engine/alpha_cutout.h"
#include "engine/builtin_scenes.h"
#include "engine/direct_light.h"
#include "engine/raster_reference.h"
#include "engine/rasterizer.h"
#include "engine/view.h"
#include "gpu_fixture.h"
#include "shared/raster.h"

namespace {

using engine::Scene;

struct GpuRaster {
  std::vector<uint64_t> visibility;
  gpu::RasterCounters counters;
};

GpuRaster rasterizeGpu(engine::Context& ctx, const Scene& scene, const glm::mat4& viewProj,
                       uint32_t width, uint32_t height) {
  engine::SceneGpu gpuScene = engine::uploadScene(ctx, scene);
  engine::Rasterizer rasterizer(ctx);
  engine::Buffer vis(ctx, engine::Rasterizer::visibilityBytes(width, height),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    rasterizer.record(cmd, gpuScene, viewProj, {&vis, 0, width, height});
  });
  GpuRaster out;
  out.visibility = vis.readbackAs<uint64_t>(ctx);
  auto counters = rasterizer.counters().readbackAs<gpu::RasterCounters>(ctx);
  out.counters = counters.at(0);
  return out;
}

// Counts pixels whose visibility entries differ and reports the first one.
::testing::AssertionResult sameVisibility(const std::vector<uint64_t>& gpu,
                                          const std::vector<uint64_t>& cpu, uint32_t width) {
  if (gpu.size() != cpu.size()) return ::testing::AssertionFailure() << "size mismatch";
  size_t differing = 0, first = 0;
  for (size_t i = 0; i < gpu.size(); ++i)
    if (gpu[i] != cpu[i] && differing++ == 0) first = i;
  if (differing == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << differing << " pixels differ; first at (" << first % width << ", " << first / width
         << "): gpu id " << (gpu[first] & 0xFFFFFFFFu) << " depth bits " << (gpu[first] >> 32)
         << ", cpu id " << (cpu[first] & 0xFFFFFFFFu) << " depth bits " << (cpu[first] >> 32);
}

// A single-material scene from raw triangles, enough for the rasterizer.
Scene meshScene(std::vector<glm::vec3> positions, std::vector<uint32_t> indices) {
  Scene s;
  s.source = "test:mesh";
  s.normals.assign(positions.size(), glm::vec3(0, 0, 1));
  s.uvs.assign(positions.size(), glm::vec2(0));
  s.positions = std::move(positions);
  s.triangleMaterial.assign(indices.size() / 3, 0);
  s.indices = std::move(indices);
  s.materials.push_back({});
  return s;
}

// Triangles of an n x n cell grid of (n+1)^2 row-major vertices, with alternating diagonals so
// that edges of every slope sign meet at the vertices.
std::vector<uint32_t> gridIndices(int n) {
  std::vector<uint32_t> idx;
  auto at = [&](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      uint32_t a = at(i, j), b = at(i + 1, j), c = at(i, j + 1), d = at(i + 1, j + 1);
      if ((i + j) % 2 == 0)
        idx.insert(idx.end(), {a, b, d, a, d, c});
      else
        idx.insert(idx.end(), {a, b, c, b, d, c});
    }
  }
  return idx;
}

// A (n+1)^2-vertex grid over [-half, half]^2 in the plane {y = height} (or z = depth for the
// vertical grid), interior vertices jittered so edges take arbitrary slopes, triangulated with
// alternating diagonals. Every interior edge is shared by exactly two triangles.
Scene jitteredGrid(int n, float half, bool horizontal, float offset, uint32_t seed) {
  std::mt19937 rng(seed);
  // +-0.15 cell: small enough that every quad stays convex (no fold-overs), large enough that
  // edges take arbitrary slopes.
  auto jitter = [&]() { return (static_cast<float>(rng() >> 8) * 0x1p-24f - 0.5f) * 0.3f; };
  std::vector<glm::vec3> p;
  float step = 2.0f * half / static_cast<float>(n);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      float a = -half + step * static_cast<float>(i), b = -half + step * static_cast<float>(j);
      if (i > 0 && i < n && j > 0 && j < n) {
        a += jitter() * step;
        b += jitter() * step;
      }
      p.push_back(horizontal ? glm::vec3(a, offset, b) : glm::vec3(a, b, offset));
    }
  }
  return meshScene(std::move(p), gridIndices(n));
}

class Rasterizer : public testing_gpu::GpuTest {};

TEST_F(Rasterizer, MatchesReferenceOnBuiltinSceneCameras) {
  const uint32_t w = 128, h = 72;
  for (const std::string& name : engine::builtinSceneNames()) {
    SCOPED_TRACE(name);
    Scene scene = engine::makeBuiltinScene(name);
    engine::View view = engine::cameraView(scene.cameras.at(0), w, h);
    GpuRaster gpu = rasterizeGpu(ctx(), scene, view.viewProj, w, h);
    engine::ReferenceRaster cpu = engine::rasterizeReference(scene, view.viewProj, w, h);
    EXPECT_TRUE(sameVisibility(gpu.visibility, cpu.visibility, w));
    EXPECT_EQ(gpu.counters.dropped, 0u);
    size_t covered = 0;
    for (uint64_t v : cpu.visibility) covered += v != ~uint64_t{0};
    EXPECT_GT(covered, size_t{w} * h / 2) << "the camera should mostly see the scene";
  }
}

TEST_F(Rasterizer, MatchesReferenceOnShadowViews) {
  // Light views exercise perspective cones from inside the scene, cube faces and orthographic
  // projections, and many triangles cut by the near plane.
  const uint32_t size = 64;
  for (const std::string& name : engine::builtinSceneNames()) {
    Scene scene = engine::makeBuiltinScene(name);
    engine::LightSetup setup = engine::buildLightSetup(scene, {size, true});
    ASSERT_FALSE(setup.views.empty()) << name;
    for (size_t v = 0; v < setup.views.size(); ++v) {
      SCOPED_TRACE(name + " shadow view " + std::to_string(v));
      const glm::mat4& vp = setup.views[v].viewProj;
      GpuRaster gpu = rasterizeGpu(ctx(), scene, vp, size, size);
      EXPECT_TRUE(sameVisibility(
          gpu.visibility, engine::rasterizeReference(scene, vp, size, size).visibility, size));
    }
  }
}

TEST_F(Rasterizer, JitteredGridIsWatertight) {
  // A grid much larger than the view, facing the camera: every pixel is covered exactly once.
  const uint32_t w = 97, h = 61;  // odd sizes: pixel centres fall on no special fractions
  Scene grid = jitteredGrid(24, 2.0f, false, 0.0f, 7);
  glm::mat4 view = engine::lookAlong(glm::vec3(0.05f, -0.03f, 2.0f), glm::vec3(0.1f, 0.05f, -1.0f),
                                     glm::vec3(0, 1, 0));
  glm::mat4 vp =
      engine::perspectiveVulkan(0.8f, static_cast<float>(w) / static_cast<float>(h), 0.1f, 10.0f) *
      view;
  engine::ReferenceRaster cpu = engine::rasterizeReference(grid, vp, w, h);
  for (size_t i = 0; i < cpu.coverage.size(); ++i)
    ASSERT_EQ(cpu.coverage[i], 1u) << "pixel (" << i % w << ", " << i / w << ")";
  GpuRaster gpu = rasterizeGpu(ctx(), grid, vp, w, h);
  EXPECT_TRUE(sameVisibility(gpu.visibility, cpu.visibility, w));
}

TEST_F(Rasterizer, PixelAlignedGridExercisesTheFillRule) {
  // Vertices on pixel centres of an orthographic view: horizontal, vertical and diagonal edges
  // run exactly through sample points, so only the fill rule decides who owns them.
  const uint32_t size = 64;
  std::vector<glm::vec3> p;
  const int n = 20;  // 20 cells of 4 pixels: the grid overhangs the 64-pixel view
  auto ndc = [&](int k) {
    return (static_cast<float>(4 * k - 8) + 0.5f) / static_cast<float>(size) * 2.0f - 1.0f;
  };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) p.push_back(glm::vec3(ndc(i), -ndc(j), 0.0f));
  Scene grid = meshScene(std::move(p), gridIndices(n));
  // Camera at z = 1 looking down -Z with a [-1, 1]^2 orthographic window.
  glm::mat4 vp = engine::orthographicVulkan(1.0f, 1.0f, 0.5f, 1.5f) *
                 engine::lookAlong(glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
  engine::ReferenceRaster cpu = engine::rasterizeReference(grid, vp, size, size);
  for (size_t i = 0; i < cpu.coverage.size(); ++i)
    ASSERT_EQ(cpu.coverage[i], 1u) << "pixel (" << i % size << ", " << i / size << ")";
  GpuRaster gpu = rasterizeGpu(ctx(), grid, vp, size, size);
  EXPECT_TRUE(sameVisibility(gpu.visibility, cpu.visibility, size));
}

TEST_F(Rasterizer, NearPlaneClippedGroundIsWatertight) {
  // A ground grid that extends behind the camera: triangles straddle the near plane and the
  // guard band. Pixels whose ray meets the ground well inside the grid are covered exactly once;
  // no pixel is covered twice anywhere.
  const uint32_t w = 101, h = 67;
  const float half = 30.0f, ground = -1.0f;
  Scene grid = jitteredGrid(40, half, true, ground, 11);
  glm::vec3 eye(0.3f, 0.0f, 0.2f);
  glm::mat4 view = engine::lookAlong(eye, glm::vec3(0.2f, -0.25f, -1.0f), glm::vec3(0, 1, 0));
  glm::mat4 proj =
      engine::perspectiveVulkan(1.2f, static_cast<float>(w) / static_cast<float>(h), 0.05f, 0.0f);
  glm::mat4 vp = proj * view;
  glm::mat4 inv = glm::inverse(vp);
  engine::ReferenceRaster cpu = engine::rasterizeReference(grid, vp, w, h);
  size_t checked = 0;
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      uint32_t count = cpu.coverage[y * w + x];
      ASSERT_LE(count, 1u) << "double coverage at (" << x << ", " << y << ")";
      glm::vec2 ndc((static_cast<float>(x) + 0.5f) / static_cast<float>(w) * 2.0f - 1.0f,
                    (static_cast<float>(y) + 0.5f) / static_cast<float>(h) * 2.0f - 1.0f);
      glm::vec4 a = inv * glm::vec4(ndc, 0.0f, 1.0f), b = inv * glm::vec4(ndc, 0.5f, 1.0f);
      glm::vec3 o = glm::vec3(a) / a.w, d = glm::vec3(b) / b.w - o;
      if (d.y >= 0.0f) continue;  // above the horizon
      float t = (ground - o.y) / d.y;
      glm::vec3 hit = o + t * d;
      if (std::abs(hit.x) > 0.9f * half || std::abs(hit.z) > 0.9f * half) continue;
      EXPECT_EQ(count, 1u) << "hole at (" << x << ", " << y << ")";
      ++checked;
    }
  }
  EXPECT_GT(checked, size_t{w} * h / 4);
  GpuRaster gpu = rasterizeGpu(ctx(), grid, vp, w, h);
  EXPECT_TRUE(sameVisibility(gpu.visibility, cpu.visibility, w));
  EXPECT_EQ(gpu.counters.dropped, 0u);
}

TEST_F(Rasterizer, AlphaCutoutsMatchTheTwinAndCutTheirShare) {
  // A ground of alpha-tested triangles, some straddling the near plane and the guard band, with
  // a transformed, random-alpha texture whose 13 x 7 texels are resampled to the packed 16 x 16
  // layer, and an opaque wall behind it. The twin evaluates the same fp32 operations, so the
  // visibility must match bit for bit; the ground keeps about its texels' opaque share.
  const uint32_t w = 101, h = 67;
  Scene scene = jitteredGrid(40, 30.0f, true, -1.0f, 11);
  const size_t groundTriangles = scene.triangleCount();
  Scene wall = jitteredGrid(4, 40.0f, false, -25.0f, 5);
  const auto base = static_cast<uint32_t>(scene.positions.size());
  scene.positions.insert(scene.positions.end(), wall.positions.begin(), wall.positions.end());
  scene.normals.insert(scene.normals.end(), wall.normals.begin(), wall.normals.end());
  for (uint32_t i : wall.indices) scene.indices.push_back(base + i);
  scene.triangleMaterial.resize(scene.triangleCount(), 1);
  scene.uvs.clear();
  for (const glm::vec3& p : scene.positions) scene.uvs.push_back(glm::vec2(p.x, p.z) * 0.37f);
  engine::Texture texture{"random alpha", 13, 7, {}};
  std::mt19937 rng(5);
  for (int i = 0; i < 13 * 7; ++i)
    texture.rgba8.insert(texture.rgba8.end(), {200, 200, 200, static_cast<uint8_t>(rng() & 255)});
  scene.textures.push_back(texture);
  engine::Material& ground = scene.materials[0];
  ground.baseColorTexture = 0;
  ground.baseColorFactor.a = 0.9f;
  ground.alphaCutoff = 0.5f;
  ground.baseColorTransform = {glm::vec2(0.1f, -0.2f), 0.3f, glm::vec2(1.7f, 0.8f)};
  scene.materials.push_back({});  // the wall, opaque

  glm::vec3 eye(0.3f, 0.0f, 0.2f);
  glm::mat4 view = engine::lookAlong(eye, glm::vec3(0.2f, -0.25f, -1.0f), glm::vec3(0, 1, 0));
  glm::mat4 vp =
      engine::perspectiveVulkan(1.2f, static_cast<float>(w) / static_cast<float>(h), 0.05f, 0.0f) *
      view;
  engine::ReferenceRaster cpu = engine::rasterizeReference(scene, vp, w, h);
  GpuRaster gpu = rasterizeGpu(ctx(), scene, vp, w, h);
  EXPECT_TRUE(sameVisibility(gpu.visibility, cpu.visibility, w));
  EXPECT_EQ(gpu.counters.dropped, 0u);

  // Cut pixels show the wall (or the sky), never another ground triangle; the ground keeps
  // about the share of the packed layer's texels that pass.
  Scene opaque = scene;
  opaque.materials[0].alphaCutoff = 0.0f;
  engine::ReferenceRaster full = engine::rasterizeReference(opaque, vp, w, h);
  auto isGround = [&](uint64_t v) {
    return v != ~uint64_t{0} && (v & 0xFFFFFFFFu) < groundTriangles;
  };
  size_t groundPixels = 0, kept = 0;
  for (size_t i = 0; i < full.visibility.size(); ++i) {
    if (!isGround(full.visibility[i])) continue;
    ++groundPixels;
    if (isGround(cpu.visibility[i])) {
      ++kept;
      EXPECT_EQ(cpu.visibility[i], full.visibility[i]) << "pixel " << i;
    }
  }
  const engine::AlphaCutouts cutouts(scene);
  size_t passing = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      passing += cutouts.opaque(0, glm::vec2((float(x) + 0.5f) / 16.0f, (float(y) + 0.5f) / 16.0f));
  const double share = static_cast<double>(passing) / 256.0;
  ASSERT_GT(groundPixels, size_t{w} * h / 4);
  // About 3 000 pixels over many texels: a binomial spread of ~0.01; 0.06 leaves room for the
  // perspective's uneven weighting of the 256 texels.
  EXPECT_NEAR(static_cast<double>(kept) / static_cast<double>(groundPixels), share, 0.06);
  EXPECT_GT(share, 0.2);
  EXPECT_LT(share, 0.8);
}

TEST_F(Rasterizer, LargeTrianglesInALargeViewMatchTheTwin) {
  // Two 4 m quads, 1 m apart, below a spot's 1024^2 view: four triangles whose pixel boxes hold
  // 4 M pixels, which one work group once walked alone, until lavapipe ended its loop after
  // 65 535 iterations and the nearer quad went missing (shared/raster.h, RASTER_CHUNK_PIXELS).
  // With an alpha-tested checker on the nearer quad too.
  const uint32_t size = 1024;
  Scene scene = jitteredGrid(1, 2.0f, true, 1.0f, 1);
  Scene floor = jitteredGrid(1, 3.0f, true, 0.0f, 1);
  const auto base = static_cast<uint32_t>(scene.positions.size());
  scene.positions.insert(scene.positions.end(), floor.positions.begin(), floor.positions.end());
  scene.normals.insert(scene.normals.end(), floor.normals.begin(), floor.normals.end());
  scene.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 0}, {0, 0}, {0, 0}, {0, 0}};
  for (uint32_t i : floor.indices) scene.indices.push_back(base + i);
  scene.triangleMaterial = {0, 0, 1, 1};
  scene.materials.push_back({});
  scene.textures.push_back(
      {"checker",
       2,
       2,
       {255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 255}});
  scene.materials[0].baseColorTexture = 0;
  const glm::mat4 vp =
      engine::perspectiveVulkan(1.0f, 1.0f, 0.05f, 10.0f) *
      engine::lookAlong(glm::vec3(0, 3, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1));
  for (const float cutoff : {0.0f, 0.5f}) {
    SCOPED_TRACE(cutoff > 0.0f ? "alpha-tested" : "opaque");
    scene.materials[0].alphaCutoff = cutoff;
    engine::ReferenceRaster cpu = engine::rasterizeReference(scene, vp, size, size);
    GpuRaster gpu = rasterizeGpu(ctx(), scene, vp, size, size);
    EXPECT_TRUE(sameVisibility(gpu.visibility, cpu.visibility, size));
    EXPECT_GE(gpu.counters.groupsY, 4u * size * size / RASTER_CHUNK_PIXELS - 4u);
    size_t nearer = 0;
    for (uint64_t v : gpu.visibility) nearer += v != ~uint64_t{0} && (v & 0xFFFFFFFFu) < 2u;
    // The view's half width at the nearer quad is 2 tan(0.5) = 1.09 m < 2 m: it fills the view,
    // or the opaque half of it.
    EXPECT_EQ(nearer, cutoff > 0.0f ? size_t{size} * size / 2 : size_t{size} * size);
  }
}

TEST_F(Rasterizer, EmptyViewLeavesBufferEmpty) {
  // Everything behind the camera: all triangles are rejected, no work group is dispatched.
  Scene grid = jitteredGrid(4, 1.0f, false, 5.0f, 3);
  glm::mat4 vp = engine::perspectiveVulkan(0.8f, 1.0f, 0.1f, 0.0f) *
                 engine::lookAlong(glm::vec3(0), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
  GpuRaster gpu = rasterizeGpu(ctx(), grid, vp, 32, 32);
  for (uint64_t v : gpu.visibility) ASSERT_EQ(v, ~uint64_t{0});
  EXPECT_EQ(gpu.counters.triangleCount, 0u);
}

}  // namespace
