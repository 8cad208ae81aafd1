// The compute rasterizer: scene triangles -> visibility buffer, one uint64 per pixel holding
// (float depth bits << 32) | triangle id, the nearest surface winning; all ones = empty.
// Two dispatches: raster_setup (per triangle: transform, clip, snap, append) and an indirect
// raster_triangles (coverage with a top-left fill rule, 64-bit atomicMin). No back-face
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

  // The counters of the last recorded view (tests check `dropped` stays 0).
  const Buffer& counters() const { return counters_; }

  static VkDeviceSize visibilityBytes(uint32_t width, uint32_t height) {
    return VkDeviceSize{width} * height * sizeof(uint64_t);
  }

 private:
  void reserve(uint32_t triangleCount);

  Context& ctx_;
  ComputeProgram setup_;
  ComputeProgram coverage_;
  ComputeProgram alphaCoverage_;  // with the alpha test, for scenes with SceneGpu::alphaCutouts
  Buffer triangles_;              // gpu::RasterTriangle list
  Buffer groupAreas_;             // pixel-box area per RASTER_GROUP_SIZE entries of the list
  Buffer counters_;               // gpu::RasterCounters
  uint32_t capacity_ = 0;
};

}  // namespace engine
