#include "engine/rasterizer.h"

#include <algorithm>

#include "engine/commands.h"
#include "engine/raster_clusters.h"
#include "shared/raster.h"
#include "spirv/raster_cull.h"
#include "spirv/raster_setup.h"
#include "spirv/raster_triangles.h"

namespace engine {

namespace {

// raster_triangles.comp with its alpha test (kAlphaTest) compiled in or out.
ComputeProgram coverageProgram(Context& ctx, uint32_t alphaTest) {
  const uint32_t specialization[] = {alphaTest};
  const VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  return ComputeProgram(ctx, alphaTest ? "raster_triangles (alpha test)" : "raster_triangles",
                        kRasterTrianglesSpv,
                        {storage, storage, storage, storage, storage, storage, storage,
                         VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, storage},
                        sizeof(gpu::RasterTrianglesPush), specialization);
}

// raster_setup.comp's two passes: setup (kClipPass = 0) or the clipping of what it listed.
ComputeProgram setupProgram(Context& ctx, uint32_t clipPass) {
  const uint32_t specialization[] = {clipPass};
  const VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  return ComputeProgram(ctx, clipPass ? "raster_setup (clip)" : "raster_setup", kRasterSetupSpv,
                        {storage, storage, storage, storage, storage, storage, storage},
                        sizeof(gpu::RasterSetupPush), specialization);
}

}  // namespace

Rasterizer::Rasterizer(Context& ctx)
    : ctx_(ctx),
      cull_(ctx, "raster_cull", kRasterCullSpv,
            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
             VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
            sizeof(gpu::RasterSetupPush)),
      setup_(setupProgram(ctx, 0)),
      clip_(setupProgram(ctx, 1)),
      coverage_(coverageProgram(ctx, 0)),
      alphaCoverage_(coverageProgram(ctx, 1)),
      counters_(ctx, sizeof(gpu::RasterCounters),
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                MemoryUsage::GpuOnly) {}

void Rasterizer::reserve(uint32_t triangleCount) {
  // Most triangles yield at most one entry (frustum-culled ones none); near-plane clipping adds
  // one more, guard-band clipping up to four more but only for huge triangles. Twice the input
  // plus slack covers real scenes; overflow is counted in RasterCounters::dropped.
  uint32_t needed = 2 * triangleCount + 1024;
  if (needed <= capacity_) return;
  triangles_ = Buffer(ctx_, VkDeviceSize{needed} * sizeof(gpu::RasterTriangle),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly);
  groupAreas_ = Buffer(ctx_, VkDeviceSize{groupCount(needed, RASTER_GROUP_SIZE)} * sizeof(uint32_t),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly);
  clipList_ = Buffer(ctx_, VkDeviceSize{std::max(triangleCount, 1u)} * sizeof(uint32_t),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly);
  clusterList_ =
      Buffer(ctx_, VkDeviceSize{std::max(clusterCount(triangleCount), 1u)} * sizeof(uint32_t),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly);
  capacity_ = needed;
}

RasterTransform rasterTransform(const glm::mat4& viewProj) {
  const glm::dmat4 m(viewProj);
  // Row k of the transform as a function of the point: clip_k = sum_c m[c][k] p_c + m[3][k].
  auto row = [&](int k) { return glm::dvec4(m[0][k], m[1][k], m[2][k], m[3][k]); };
  const bool perspective = glm::dvec3(row(3)) != glm::dvec3(0.0);
  // The eye: x = y = 0 and w = 0 (perspective), or z = 0 (orthographic: the near plane).
  const glm::dvec4 third = perspective ? row(3) : row(2);
  const glm::dmat3 a =
      glm::transpose(glm::dmat3(glm::dvec3(row(0)), glm::dvec3(row(1)), glm::dvec3(third)));
  const glm::dvec3 b(-row(0).w, -row(1).w, -third.w);
  const glm::dvec3 origin =
      std::abs(glm::determinant(a)) > 0.0 ? glm::inverse(a) * b : glm::dvec3(0.0);
  glm::dmat4 relative = m;
  relative[3] = m * glm::dvec4(origin, 1.0);
  return {glm::mat4(relative), glm::vec3(origin)};
}

glm::vec4 rasterClip(const RasterTransform& t, const glm::vec3& world) {
  const glm::mat4& m = t.matrix;
  const glm::vec3 p(world.x - t.origin.x, world.y - t.origin.y, world.z - t.origin.z);
  glm::vec4 r;
  for (int k = 0; k < 4; ++k) {
    float a = m[0][k] * p.x;
    float b = m[1][k] * p.y;
    float c = m[2][k] * p.z;
    float s = a + b;
    s = s + c;
    r[k] = s + m[3][k];
  }
  return r;
}

void Rasterizer::record(VkCommandBuffer cmd, const SceneGpu& scene, const glm::mat4& viewProj,
                        const RasterTarget& target, GpuProfiler* profiler) {
  record(cmd, scene, rasterTransform(viewProj), target, profiler);
}

void Rasterizer::record(VkCommandBuffer cmd, const SceneGpu& scene,
                        const RasterTransform& transform, const RasterTarget& target,
                        GpuProfiler* profiler) {
  if (target.width == 0 || target.height == 0 || target.width > RASTER_MAX_VIEWPORT ||
      target.height > RASTER_MAX_VIEWPORT)
    throw Error("rasterizer: viewport " + std::to_string(target.width) + "x" +
                std::to_string(target.height) + " outside 1.." +
                std::to_string(RASTER_MAX_VIEWPORT));
  reserve(scene.triangleCount);
  VkDeviceSize visBytes = visibilityBytes(target.width, target.height);

  {
    ProfileScope scope(profiler, cmd, "raster setup");
    gpu::RasterCounters zero{0, 0, 1, 1, 0, 0, 1, 1, 0, 1, 1, 0};
    updateBuffer(cmd, counters_, &zero, sizeof(zero));
    fillBuffer(cmd, *target.visibility, 0xFFFFFFFFu, target.offset, visBytes);
    fillBuffer(cmd, groupAreas_, 0u);
    gpu::RasterSetupPush push{transform.matrix,
                              glm::vec4(transform.origin, 0.0f),
                              {target.width, target.height},
                              scene.triangleCount,
                              capacity_,
                              scene.vertexCount,
                              cullClusters_ ? 1u : 0u,
                              0,
                              0};
    cull_.dispatch(cmd,
                   {Binding::storage(scene.clusters), Binding::storage(clusterList_),
                    Binding::storage(counters_)},
                   push, groupCount(clusterCount(scene.triangleCount), RASTER_GROUP_SIZE));
    computeBarrier(cmd);
    const std::initializer_list<Binding> bindings = {
        Binding::storage(scene.vertices), Binding::storage(scene.indices),
        Binding::storage(triangles_),     Binding::storage(counters_),
        Binding::storage(groupAreas_),    Binding::storage(clipList_),
        Binding::storage(clusterList_)};
    setup_.dispatchIndirect(cmd, bindings, push, counters_,
                            offsetof(gpu::RasterCounters, clusterCount));
    computeBarrier(cmd);
    clip_.dispatchIndirect(cmd, bindings, push, counters_,
                           offsetof(gpu::RasterCounters, clipGroupsX));
    computeBarrier(cmd);
  }
  {
    ProfileScope scope(profiler, cmd, "raster coverage");
    gpu::RasterTrianglesPush push{transform.matrix,
                                  glm::vec4(transform.origin, 0.0f),
                                  {target.width, target.height},
                                  capacity_,
                                  scene.materialCount};
    (scene.alphaCutouts ? alphaCoverage_ : coverage_)
        .dispatchIndirect(
            cmd,
            {Binding::storage(triangles_), Binding::storage(counters_),
             Binding::storage(*target.visibility, target.offset, visBytes),
             Binding::storage(scene.vertices), Binding::storage(scene.indices),
             Binding::storage(scene.triangleMaterials), Binding::storage(scene.materials),
             Binding::sampled(scene.baseColorTextures, scene.sampler.handle()),
             Binding::storage(groupAreas_)},
            push, counters_, offsetof(gpu::RasterCounters, groupsX));
    computeBarrier(cmd);
  }
}

}  // namespace engine
