// The compute rasterizer: scene triangles -> visibility buffer, one uint64 per pixel holding
// (float depth bits << 32) | triangle id, the nearest surface winning; all ones = empty.
// Four dispatches: raster_cull (per cluster of triangles, SceneGpu::clusters: the clusters whose
// box the view may see), an indirect raster_setup over them (per triangle: transform, reject,
// snap, append; a triangle that crosses the near plane or the guard band is listed instead),
// its indirect clip pass over that list, and an indirect raster_triangles (coverage with a
// top-left fill rule, 64-bit atomicMin). No back-face
// culling, so single- and double-sided geometry both render; alpha-tested materials (glTF MASK)
// cover a pixel only where their cut-out test keeps the surface (engine/alpha_cutout.h). The
// same code renders camera views, shadow maps and reflective shadow maps.
#pragma once

#include <glm/glm.hpp>

#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/scene_gpu.h"

namespace engine {

struct RasterTarget {
  const Buffer* visibility = nullptr;  // width * height uint64 starting at `offset`
  VkDeviceSize offset = 0;             // bytes; a multiple of minStorageBufferOffsetAlignment
  uint32_t width = 0;
  uint32_t height = 0;
};

// The rasterizer's transform of world positions, shared by its setup pass and its CPU twin:
// clip = matrix x (p - origin), with origin the view's eye (where clip x = y = w = 0; for an
// orthographic view, the centre of its near plane) and matrix = viewProj x translate(origin),
// rounded to float once from double. p - origin is exact when the two are close (Sterbenz's
// lemma), so the depth order of a scene far from the world origin survives fp32: with viewProj
// applied directly, at 1 km an RSM texel's depth test picked a surface 0.78 m away.
struct RasterTransform {
  glm::mat4 matrix{1.0f};
  glm::vec3 origin{0.0f};
};
RasterTransform rasterTransform(const glm::mat4& viewProj);
// Clip coordinates of `world`, rounded as the shaders' rasterClip (raster_clip.glsl): p - origin,
// then ((m0 x + m1 y) + m2 z) + m3, each difference, product and sum rounded to float.
glm::vec4 rasterClip(const RasterTransform& transform, const glm::vec3& world);

class Rasterizer {
 public:
  explicit Rasterizer(Context& ctx);

  // Records clear + setup + coverage for one view. viewProj maps world space to Vulkan clip
  // space (x right, y down, depth [0, 1]).
  void record(VkCommandBuffer cmd, const SceneGpu& scene, const glm::mat4& viewProj,
              const RasterTarget& target, GpuProfiler* profiler = nullptr);
  // The same with the transform given directly, for a view that knows its eye and its
  // translation-free view-projection exactly (the RSM): rasterTransform's solve for the eye from
  // a rounded viewProj leaves the depth row's rounding times the distance from the world
  // origin in every depth.
  void record(VkCommandBuffer cmd, const SceneGpu& scene, const RasterTransform& transform,
              const RasterTarget& target, GpuProfiler* profiler = nullptr);

  // Off: every cluster goes through triangle setup (tests compare the two; culling is exact).
  void setClusterCulling(bool on) { cullClusters_ = on; }

  // The counters of the last recorded view (tests check `dropped` stays 0).
  const Buffer& counters() const { return counters_; }
  // The clusters the last view kept (RasterCounters::clusterCount ids, in no order).
  const Buffer& keptClusters() const { return clusterList_; }

  static VkDeviceSize visibilityBytes(uint32_t width, uint32_t height) {
    return VkDeviceSize{width} * height * sizeof(uint64_t);
  }

 private:
  void reserve(uint32_t triangleCount);
  bool cullClusters_ = true;

  Context& ctx_;
  ComputeProgram cull_;  // raster_cull: the clusters the view may see
  ComputeProgram setup_;
  ComputeProgram clip_;  // raster_setup's clip pass over the triangles setup listed
  ComputeProgram coverage_;
  ComputeProgram alphaCoverage_;  // with the alpha test, for scenes with SceneGpu::alphaCutouts
  Buffer triangles_;              // gpu::RasterTriangle list
  Buffer groupAreas_;             // pixel-box area per RASTER_GROUP_SIZE entries of the list
  Buffer counters_;               // gpu::RasterCounters
  Buffer clipList_;               // triangle ids for the clip pass, one slot per scene triangle
  Buffer clusterList_;            // the clusters raster_cull kept, one slot per cluster
  uint32_t capacity_ = 0;
};

}  // namespace engine
