// The compute rasterizer's clusters (gpu::RasterCluster, shaders/shared/raster.h): a box around
// every RASTER_GROUP_SIZE consecutive triangles, so that a view skips the clusters outside its
// frustum before triangle setup reads their vertices (raster_cull.comp). The boxes come from
// the CPU at upload (clusterBounds) or, for geometry that lives only on the GPU and may move in
// place, from raster_bounds.comp (ClusterBounds). docs/techniques/raster-culling.md.
#pragma once

#include <vector>

#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/rasterizer.h"
#include "engine/scene.h"
#include "engine/scene_gpu.h"
#include "shared/raster.h"

namespace engine {

uint32_t clusterCount(uint32_t triangleCount);

// Every cluster's box of `scene` (CPU twin of raster_bounds.comp): triangles naming a vertex
// past the end are left out, as setup leaves them out; a cluster with a position that is not
// finite is never culled.
std::vector<gpu::RasterCluster> clusterBounds(const Scene& scene);

// Whether raster_cull.comp keeps `cluster` in the view `transform` (its CPU twin).
bool clusterKept(const gpu::RasterCluster& cluster, const RasterTransform& transform);

// A buffer for the clusters of triangleCount triangles (SceneGpu::clusters).
Buffer createClusterBuffer(Context& ctx, uint32_t triangleCount);

// raster_bounds.comp: the boxes of a scene whose vertices live on the GPU.
class ClusterBounds {
 public:
  explicit ClusterBounds(Context& ctx);
  // Writes the box of every cluster of `scene` into scene.clusters.
  void record(VkCommandBuffer cmd, const SceneGpu& scene, GpuProfiler* profiler = nullptr) const;

 private:
  ComputeProgram program_;
};

}  // namespace engine
