// Cluster culling in the compute rasterizer (engine/raster_clusters.h): the GPU boxes and cull
// decisions against their CPU twins, and the rasterizer's output with culling on and off (the
// same to the bit: culling only skips what setup would reject).
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/builtin_scenes.h"
#include "engine/direct_light.h"
#include "engine/raster_clusters.h"
#include "engine/rasterizer.h"
#include "engine/view.h"
#include "gpu_fixture.h"

namespace {

using engine::Scene;

struct Culled {
  std::vector<uint64_t> visibility;
  std::vector<uint32_t> kept;  // sorted cluster ids
};

Culled rasterize(engine::Context& ctx, const engine::SceneGpu& scene, const glm::mat4& viewProj,
                 uint32_t size, bool cull) {
  engine::Rasterizer rasterizer(ctx);
  rasterizer.setClusterCulling(cull);
  engine::Buffer vis(ctx, engine::Rasterizer::visibilityBytes(size, size),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    rasterizer.record(cmd, scene, viewProj, {&vis, 0, size, size});
  });
  Culled out;
  out.visibility = vis.readbackAs<uint64_t>(ctx);
  const auto counters = rasterizer.counters().readbackAs<gpu::RasterCounters>(ctx).at(0);
  EXPECT_EQ(counters.dropped, 0u);
  out.kept = rasterizer.keptClusters().readbackAs<uint32_t>(ctx);
  out.kept.resize(counters.clusterCount);
  std::sort(out.kept.begin(), out.kept.end());
  return out;
}

std::vector<uint32_t> keptByTwin(const Scene& scene, const glm::mat4& viewProj) {
  const engine::RasterTransform t = engine::rasterTransform(viewProj);
  const std::vector<gpu::RasterCluster> clusters = engine::clusterBounds(scene);
  std::vector<uint32_t> kept;
  for (uint32_t c = 0; c < clusters.size(); ++c)
    if (engine::clusterKept(clusters[c], t)) kept.push_back(c);
  return kept;
}

size_t differing(const std::vector<uint64_t>& a, const std::vector<uint64_t>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

// Every view of `scene` that a host renders: its camera and its lights' shadow views.
std::vector<glm::mat4> viewsOf(const Scene& scene, uint32_t size) {
  std::vector<glm::mat4> views;
  for (const engine::Camera& camera : scene.cameras)
    views.push_back(engine::cameraView(camera, size, size).viewProj);
  for (const gpu::ShadowView& v : engine::buildLightSetup(scene, {size, true}).views)
    views.push_back(v.viewProj);
  return views;
}

class RasterClusters : public testing_gpu::GpuTest {};

TEST_F(RasterClusters, GpuBoxesEqualTheCpuTwin) {
  Scene scene = engine::makeBuiltinScene("sphere-room:20000");
  // A triangle naming a vertex past the end (left out of its box) and one with a NaN corner
  // (its cluster is never culled).
  scene.indices[3 * 70 + 1] = static_cast<uint32_t>(scene.positions.size());
  scene.positions[scene.indices[3 * 200]].x = std::numeric_limits<float>::quiet_NaN();
  engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
  gpuScene.clusters = engine::createClusterBuffer(ctx(), gpuScene.triangleCount);
  engine::ClusterBounds pass(ctx());
  ctx().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, gpuScene); });
  const auto gpu = gpuScene.clusters.readbackAs<gpu::RasterCluster>(ctx());
  const auto cpu = engine::clusterBounds(scene);
  ASSERT_EQ(gpu.size(), cpu.size());
  size_t notFinite = 0;
  for (size_t c = 0; c < cpu.size(); ++c) {
    SCOPED_TRACE("cluster " + std::to_string(c));
    ASSERT_EQ(gpu[c].boundsMin.w, cpu[c].boundsMin.w);
    if (cpu[c].boundsMin.w != 0.0f) {  // the box of a NaN is not compared, only the flag
      ++notFinite;
      continue;
    }
    EXPECT_EQ(glm::vec3(gpu[c].boundsMin), glm::vec3(cpu[c].boundsMin));
    EXPECT_EQ(glm::vec3(gpu[c].boundsMax), glm::vec3(cpu[c].boundsMax));
  }
  EXPECT_GE(notFinite, 1u);  // the NaN vertex's triangles may span two clusters
  EXPECT_EQ(cpu[200 / RASTER_GROUP_SIZE].boundsMin.w, 1.0f);
  // The bad triangle is left out: its cluster's box is that of its other triangles.
  Scene without = scene;
  without.indices[3 * 70 + 1] = without.indices[3 * 70];
  EXPECT_EQ(engine::clusterBounds(without)[1].boundsMax, cpu[1].boundsMax);
}

TEST_F(RasterClusters, CullingKeepsTheTwinsClustersAndChangesNoPixel) {
  const uint32_t size = 96;
  size_t culledOutside = 0, clustersOutside = 0;
  for (const std::string& name :
       {std::string("cornell"), std::string("atrium"), std::string("lounge"),
        std::string("sphere-room-outside:20000")}) {
    const Scene scene = engine::makeBuiltinScene(name);
    const engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
    const std::vector<glm::mat4> views = viewsOf(scene, size);
    for (size_t v = 0; v < views.size(); ++v) {
      SCOPED_TRACE(name + " view " + std::to_string(v));
      const Culled on = rasterize(ctx(), gpuScene, views[v], size, true);
      const Culled off = rasterize(ctx(), gpuScene, views[v], size, false);
      EXPECT_EQ(differing(on.visibility, off.visibility), 0u);
      EXPECT_EQ(on.kept, keptByTwin(scene, views[v]));
      EXPECT_EQ(off.kept.size(), engine::clusterCount(gpuScene.triangleCount));
      if (name.starts_with("sphere-room-outside") && v > 0) {  // the spot light's view
        culledOutside += off.kept.size() - on.kept.size();
        clustersOutside += off.kept.size();
      }
    }
  }
  // Nine tenths of the sphere triangles lie above the ceiling, outside the spot's view.
  EXPECT_GT(static_cast<double>(culledOutside), 0.8 * static_cast<double>(clustersOutside));
}

TEST_F(RasterClusters, ClustersOnTheFrustumsEdgeAreKept) {
  // An orthographic view of [-1, 1]^2 looking down -z; clusters of thin triangles whose boxes
  // touch or straddle its right edge x = 1, and one wholly beyond it by a hair.
  const glm::mat4 viewProj = glm::mat4(1.0f, 0, 0, 0,   //
                                       0, 1.0f, 0, 0,   //
                                       0, 0, -0.1f, 0,  //
                                       0, 0, 0.5f, 1.0f);
  Scene scene;
  scene.source = "test:edge";
  auto addCluster = [&](float x0, float x1) {  // RASTER_GROUP_SIZE triangles in [x0, x1]
    for (uint32_t t = 0; t < RASTER_GROUP_SIZE; ++t) {
      const float y = -0.9f + 1.8f * static_cast<float>(t) / RASTER_GROUP_SIZE;
      const auto first = static_cast<uint32_t>(scene.positions.size());
      scene.positions.insert(scene.positions.end(),
                             {{x0, y, 0.0f}, {x1, y, 0.0f}, {x0, y + 0.03f, 0.0f}});
      scene.indices.insert(scene.indices.end(), {first, first + 1, first + 2});
    }
  };
  addCluster(0.5f, 1.0f);     // ends on the edge
  addCluster(0.9f, 1.5f);     // straddles it
  addCluster(1.0f, 1.5f);     // starts on it: setup keeps what touches x = w
  addCluster(1.0001f, 1.5f);  // wholly outside
  scene.normals.assign(scene.positions.size(), glm::vec3(0, 0, 1));
  scene.uvs.assign(scene.positions.size(), glm::vec2(0));
  scene.triangleMaterial.assign(scene.triangleCount(), 0);
  scene.materials.push_back({});
  const engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
  const Culled on = rasterize(ctx(), gpuScene, viewProj, 64, true);
  const Culled off = rasterize(ctx(), gpuScene, viewProj, 64, false);
  EXPECT_EQ(on.kept, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(on.kept, keptByTwin(scene, viewProj));
  EXPECT_EQ(differing(on.visibility, off.visibility), 0u);
  size_t straddling = 0;  // pixels of the straddling cluster's triangles
  for (uint64_t v : on.visibility)
    straddling += v != ~uint64_t{0} && (v & 0xFFFFFFFFu) / RASTER_GROUP_SIZE == 1;
  EXPECT_GT(straddling, 0u);
}

}  // namespace
