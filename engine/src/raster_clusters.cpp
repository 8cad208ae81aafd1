#include "engine/raster_clusters.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/commands.h"
#include "spirv/raster_bounds.h"

namespace engine {

uint32_t clusterCount(uint32_t triangleCount) {
  return groupCount(triangleCount, RASTER_GROUP_SIZE);
}

std::vector<gpu::RasterCluster> clusterBounds(const Scene& scene) {
  const float inf = std::numeric_limits<float>::infinity();
  const uint32_t triangles = scene.triangleCount();
  const auto vertexCount = static_cast<uint32_t>(scene.positions.size());
  std::vector<gpu::RasterCluster> clusters(clusterCount(triangles));
  for (uint32_t c = 0; c < clusters.size(); ++c) {
    glm::vec3 lo(inf), hi(-inf);
    bool finite = true;
    const uint32_t end = std::min(triangles, (c + 1) * RASTER_GROUP_SIZE);
    for (uint32_t t = c * RASTER_GROUP_SIZE; t < end; ++t) {
      const uint32_t* corner = &scene.indices[3 * size_t{t}];
      if (corner[0] >= vertexCount || corner[1] >= vertexCount || corner[2] >= vertexCount)
        continue;
      for (int i = 0; i < 3; ++i) {
        const glm::vec3& p = scene.positions[corner[i]];
        finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
    clusters[c] = {glm::vec4(lo, finite ? 0.0f : 1.0f), glm::vec4(hi, 0.0f)};
  }
  return clusters;
}

// Mirrors clusterKept() of raster_cull.comp, each operation rounded to float in its order.
bool clusterKept(const gpu::RasterCluster& c, const RasterTransform& t) {
  if (c.boundsMin.w != 0.0f) return true;
  const glm::vec3 lo(c.boundsMin), hi(c.boundsMax);
  if (glm::any(glm::greaterThan(lo, hi))) return false;
  const glm::vec3 reach = glm::max(glm::abs(lo - t.origin), glm::abs(hi - t.origin));
  const glm::mat4& m = t.matrix;
  glm::vec4 scale;
  for (int k = 0; k < 4; ++k) {
    float s = std::abs(m[0][k]) * reach.x;
    s = s + std::abs(m[1][k]) * reach.y;
    s = s + std::abs(m[2][k]) * reach.z;
    scale[k] = s + std::abs(m[3][k]);
  }
  const float margin = 1e-5f;
  const glm::vec4 limit(margin * (scale.x + scale.w), margin * (scale.y + scale.w),
                        margin * (scale.z + scale.w), margin * scale.z);
  bool beyond[6] = {true, true, true,
                    true, true, true};  // x > w, y > w, z > w, x < -w, y < -w, z < 0
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    const glm::vec4 v = rasterClip(t, p);
    for (int k = 0; k < 3; ++k) {
      const float above = v[k] - v.w;
      beyond[k] = beyond[k] && above > limit[k];
    }
    for (int k = 0; k < 2; ++k) {
      const float below = -v[k] - v.w;
      beyond[3 + k] = beyond[3 + k] && below > limit[k];
    }
    beyond[5] = beyond[5] && -v.z > limit.w;
  }
  return std::none_of(std::begin(beyond), std::end(beyond), [](bool b) { return b; });
}

Buffer createClusterBuffer(Context& ctx, uint32_t triangleCount) {
  return Buffer(
      ctx, VkDeviceSize{std::max(clusterCount(triangleCount), 1u)} * sizeof(gpu::RasterCluster),
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly);
}

ClusterBounds::ClusterBounds(Context& ctx)
    : program_(ctx, "raster_bounds", kRasterBoundsSpv,
               {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
               sizeof(gpu::RasterBoundsPush)) {}

void ClusterBounds::record(VkCommandBuffer cmd, const SceneGpu& scene,
                           GpuProfiler* profiler) const {
  ProfileScope scope(profiler, cmd, "cluster bounds");
  gpu::RasterBoundsPush push{scene.triangleCount, scene.vertexCount, 0, 0};
  program_.dispatch(cmd,
                    {Binding::storage(scene.vertices), Binding::storage(scene.indices),
                     Binding::storage(scene.clusters)},
                    push, groupCount(clusterCount(scene.triangleCount), RASTER_GROUP_SIZE));
  computeBarrier(cmd);
}

}  // namespace engine
