#include "passes/ism.h"

#include <algorithm>
#include <bit>
#include <string>

#include "engine/commands.h"
#include "shared/vsgl.h"
#include "spirv/ism_area.h"
#include "spirv/ism_points.h"
#include "spirv/ism_positions.h"
#include "spirv/ism_pull.h"
#include "spirv/ism_push.h"
#include "spirv/ism_scan.h"
#include "spirv/ism_splat.h"
#include "spirv/ism_visibility.h"

namespace gi {

namespace {

void requirePowerOfTwo(const char* field, uint32_t value, uint32_t lo, uint32_t hi) {
  if (!std::has_single_bit(value) || value < lo || value > hi)
    throw engine::Error(std::string("ISM ") + field + " " + std::to_string(value) +
                        " is not a power of two in [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
}

void requireRange(const char* field, float value, float lo, float hi, const char* unit) {
  if (!(value >= lo && value <= hi))
    throw engine::Error(std::string("ISM ") + field + " " + std::to_string(value) +
                        " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "] " +
                        unit);
}

engine::Buffer storageBuffer(engine::Context& ctx, VkDeviceSize bytes) {
  return engine::Buffer(ctx, std::max<VkDeviceSize>(bytes, 4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        engine::MemoryUsage::GpuOnly);
}

std::vector<VkDescriptorType> buffers(size_t count) {
  return std::vector<VkDescriptorType>(count, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

}  // namespace

void validateIsmSettings(const IsmSettings& settings) {
  requirePowerOfTwo("mapSize", settings.mapSize, 16, 256);
  requirePowerOfTwo("pointCount", settings.pointCount, 1u << 10, 1u << 22);
  requirePowerOfTwo("pointsPerVsgl", settings.pointsPerVsgl, 64, settings.pointCount);
  requireRange("depthBias", settings.depthBias, 0.0f, 10.0f, "m");
  requireRange("slopeBias", settings.slopeBias, 0.0f, 16.0f, "texels");
  requireRange("centreOffset", settings.centreOffset, 0.0f, 10.0f, "m");
  if (settings.pcf > ISM_MAX_PCF)
    throw engine::Error("ISM pcf " + std::to_string(settings.pcf) +
                        " is not 0 (nearest), 1 (bilinear 2x2) or 2 (box 3x3)");
}

Ism::Ism(engine::Context& ctx, const IsmSettings& settings, uint32_t maxVsgls)
    : ctx_(ctx), settings_(settings), maxVsgls_(maxVsgls) {
  validateIsmSettings(settings);
  // Tiles per row: the power of two at or above sqrt(maxVsgls), so the atlas is about square.
  tilesPerRowLog2_ = static_cast<uint32_t>(std::bit_width(maxVsgls - 1) + 1) / 2;
  const uint32_t tilesPerRow = 1u << tilesPerRowLog2_;
  const uint32_t rows = (maxVsgls + tilesPerRow - 1) / tilesPerRow;
  const uint32_t limit = ctx.properties().limits.maxImageDimension2D;
  if (maxVsgls < 1 || maxVsgls > 65535)  // the splat's work groups
    throw engine::Error("ISM maxVsgls " + std::to_string(maxVsgls) + " is outside [1, 65535]");
  if (tilesPerRow * settings.mapSize > limit)
    throw engine::Error("ISM maxVsgls " + std::to_string(maxVsgls) + " at mapSize " +
                        std::to_string(settings.mapSize) + " needs an atlas wider than the " +
                        std::to_string(limit) + " texels the device allows");
  area_ =
      engine::ComputeProgram(ctx, "ism_area", kIsmAreaSpv, buffers(3), sizeof(gpu::IsmAreaPush));
  scan_ =
      engine::ComputeProgram(ctx, "ism_scan", kIsmScanSpv, buffers(1), sizeof(gpu::IsmAreaPush));
  for (uint32_t alphaTest : {0u, 1u}) {
    const uint32_t specialization[] = {alphaTest};
    std::vector<VkDescriptorType> bindings = buffers(6);
    bindings.push_back(VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    pointsPrograms_[alphaTest] =
        engine::ComputeProgram(ctx, alphaTest ? "ism_points (alpha test)" : "ism_points",
                               kIsmPointsSpv, bindings, sizeof(gpu::IsmPointsPush), specialization);
  }
  positionsProgram_ =
      engine::ComputeProgram(ctx, "ism_positions", kIsmPositionsSpv,
                             {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                              VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                             sizeof(gpu::IsmPositionsPush));
  splat_ =
      engine::ComputeProgram(ctx, "ism_splat", kIsmSplatSpv,
                             {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                              VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                             sizeof(gpu::IsmSplatPush));
  const std::vector<VkDescriptorType> twoImages(2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  pull_ =
      engine::ComputeProgram(ctx, "ism_pull", kIsmPullSpv, twoImages, sizeof(gpu::IsmPullPushPush));
  push_ =
      engine::ComputeProgram(ctx, "ism_push", kIsmPushSpv, twoImages, sizeof(gpu::IsmPullPushPush));
  visibility_ =
      engine::ComputeProgram(ctx, "ism_visibility", kIsmVisibilitySpv,
                             {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                             sizeof(gpu::IsmVisibilityPush));
  points_ = storageBuffer(ctx, VkDeviceSize{settings.pointCount} * sizeof(gpu::IsmPoint));
  engine::ImageDesc positions;
  positions.width = ISM_POSITIONS_WIDTH;
  positions.height = settings.pointCount / ISM_POSITIONS_WIDTH;
  positions.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  positions_ = engine::Image(ctx, positions);
  engine::ImageDesc atlas;
  atlas.width = tilesPerRow * settings.mapSize;
  atlas.height = rows * settings.mapSize;
  atlas.mips = static_cast<uint32_t>(std::countr_zero(settings.mapSize)) + 1;
  atlas.format = VK_FORMAT_R32_UINT;
  atlas_ = engine::Image(ctx, atlas);
  // GENERAL for the object's life, recorded before the first frame that uses them (on a host's
  // device: at its next recordDeferredSetup).
  engine::initialLayout(ctx, positions_, VK_IMAGE_LAYOUT_GENERAL);
  engine::initialLayout(ctx, atlas_, VK_IMAGE_LAYOUT_GENERAL);
}

static_assert(IsmNearest == ISM_PCF_NEAREST && IsmBilinear == ISM_PCF_BILINEAR &&
                  IsmBox3 == ISM_PCF_BOX3,
              "gi::IsmFilter (settings.h) names the ISM_PCF_* values of shared/ism.h");

glm::uvec2 Ism::tileOrigin(uint32_t k) const {
  const uint32_t mask = (1u << tilesPerRowLog2_) - 1;
  return glm::uvec2(k & mask, k >> tilesPerRowLog2_) * settings_.mapSize;
}

gpu::IsmParams Ism::params() const {
  gpu::IsmParams p{};
  p.mapSize = settings_.mapSize;
  p.tilesPerRowLog2 = tilesPerRowLog2_;
  p.pcf = settings_.pcf;
  p.depthBias = settings_.depthBias;
  p.slopeBias = settings_.slopeBias;
  p.centreOffset = settings_.centreOffset;
  return p;
}

void Ism::recordPoints(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                       engine::GpuProfiler* profiler) {
  using engine::Binding;
  engine::ProfileScope scope(profiler, cmd, "ism points");
  const uint32_t triangles = scene.triangleCount;
  pointsRecorded_ = true;
  pointsTriangleCount_ = triangles;
  if (triangles == 0) {
    engine::fillBuffer(cmd, points_, ISM_NO_TRIANGLE);
    return;
  }
  if (cdf_.size() < VkDeviceSize{triangles} * sizeof(float))
    cdf_ = storageBuffer(ctx_, VkDeviceSize{triangles} * sizeof(float));
  const gpu::IsmAreaPush areaPush{triangles, scene.vertexCount, 0, 0};
  area_.dispatch(
      cmd,
      {Binding::storage(scene.vertices), Binding::storage(scene.indices), Binding::storage(cdf_)},
      areaPush, engine::groupCount(triangles, ISM_GROUP_SIZE));
  engine::computeBarrier(cmd);
  scan_.dispatch(cmd, {Binding::storage(cdf_)}, areaPush, 1);
  engine::computeBarrier(cmd);
  const gpu::IsmPointsPush pointsPush{triangles, settings_.pointCount, scene.materialCount, 0};
  pointsPrograms_[scene.alphaCutouts ? 1 : 0].dispatch(
      cmd,
      {Binding::storage(cdf_), Binding::storage(points_), Binding::storage(scene.vertices),
       Binding::storage(scene.indices), Binding::storage(scene.triangleMaterials),
       Binding::storage(scene.materials),
       Binding::sampled(scene.baseColorTextures, scene.sampler.handle())},
      pointsPush, engine::groupCount(settings_.pointCount, ISM_GROUP_SIZE));
  engine::computeBarrier(cmd);
}

void Ism::checkCount(uint32_t vsglCount) const {
  if (vsglCount > maxVsgls_)
    throw engine::Error("ISM vsglCount " + std::to_string(vsglCount) + " exceeds the " +
                        std::to_string(maxVsgls_) + " the atlas was made for");
}

void Ism::recordBuild(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                      const engine::Buffer& vsgls, uint32_t vsglCount,
                      engine::GpuProfiler* profiler) {
  recordPositions(cmd, scene, vsglCount, profiler);
  recordSplat(cmd, vsgls, vsglCount, profiler);
  recordPullPush(cmd, vsglCount, profiler);
}

void Ism::recordPositions(VkCommandBuffer cmd, const engine::SceneGpu& scene, uint32_t vsglCount,
                          engine::GpuProfiler* profiler) {
  using engine::Binding;
  if (!pointsRecorded_)
    throw engine::Error(
        "ISM: recordPositions before recordPoints (the point pool is not generated)");
  if (scene.triangleCount != pointsTriangleCount_)
    throw engine::Error("ISM: the scene has " + std::to_string(scene.triangleCount) +
                        " triangles but the points were made for " +
                        std::to_string(pointsTriangleCount_) +
                        " (call recordPoints after a scene change)");
  checkCount(vsglCount);
  if (vsglCount == 0) return;
  const uint32_t m = settings_.pointsPerVsgl;
  const uint32_t stride = settings_.pointCount / m;
  engine::ProfileScope scope(profiler, cmd, "ism positions");
  const gpu::IsmPositionsPush push{m, stride, std::min(vsglCount, stride), 0};
  positionsProgram_.dispatch(cmd,
                             {Binding::storage(points_), Binding::storage(scene.vertices),
                              Binding::storage(scene.indices), Binding::storageImage(positions_)},
                             push, engine::groupCount(m, ISM_GROUP_SIZE), push.classCount);
  engine::computeBarrier(cmd);  // the splat reads them
}

void Ism::recordSplat(VkCommandBuffer cmd, const engine::Buffer& vsgls, uint32_t vsglCount,
                      engine::GpuProfiler* profiler) {
  using engine::Binding;
  checkCount(vsglCount);
  if (vsgls.size() < VkDeviceSize{vsglCount} * sizeof(gpu::Vsgl))
    throw engine::Error("ISM vsglCount " + std::to_string(vsglCount) + " exceeds the VSGL buffer");
  if (vsglCount == 0) return;
  const uint32_t m = settings_.pointsPerVsgl;
  const uint32_t stride = settings_.pointCount / m;
  engine::ProfileScope scope(profiler, cmd, "ism splat");
  // Barriers around the clear: earlier reads of the atlas, then the splat's writes.
  engine::imageBarrier(cmd, atlas_, VK_IMAGE_LAYOUT_GENERAL);
  VkClearColorValue empty{};
  empty.uint32[0] = ISM_EMPTY;
  const VkImageSubresourceRange level0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, atlas_.handle(), VK_IMAGE_LAYOUT_GENERAL, &empty, 1, &level0);
  engine::imageBarrier(cmd, atlas_, VK_IMAGE_LAYOUT_GENERAL);
  gpu::IsmSplatPush push{};
  push.params = params();
  push.pointsPerVsgl = m;
  push.stride = stride;
  splat_.dispatch(cmd,
                  {Binding::storageImage(positions_), Binding::storage(vsgls),
                   Binding::storageImage(atlas_, 0)},
                  push, vsglCount);
  engine::computeBarrier(cmd);
}

void Ism::recordPullPush(VkCommandBuffer cmd, uint32_t vsglCount, engine::GpuProfiler* profiler) {
  using engine::Binding;
  checkCount(vsglCount);
  if (vsglCount == 0) return;
  engine::ProfileScope scope(profiler, cmd, "ism pull-push");
  const auto levels = static_cast<uint32_t>(std::countr_zero(settings_.mapSize));
  // Only the rows of tiles in use.
  const uint32_t tilesPerRow = 1u << tilesPerRowLog2_;
  const uint32_t width = tilesPerRow * settings_.mapSize;
  const uint32_t height = (vsglCount + tilesPerRow - 1) / tilesPerRow * settings_.mapSize;
  auto constants = [&](uint32_t level) {
    return gpu::IsmPullPushPush{glm::uvec2(width >> level, height >> level), levels - level, level};
  };
  for (uint32_t level = 1; level <= levels; ++level) {
    const gpu::IsmPullPushPush push = constants(level);
    pull_.dispatch(cmd,
                   {Binding::storageImage(atlas_, level - 1), Binding::storageImage(atlas_, level)},
                   push, engine::groupCount(push.size.x, ISM_IMAGE_GROUP),
                   engine::groupCount(push.size.y, ISM_IMAGE_GROUP));
    engine::computeBarrier(cmd);
  }
  for (uint32_t level = levels; level-- > 0;) {
    const gpu::IsmPullPushPush push = constants(level);  // one thread per 2 x 2 texels
    push_.dispatch(cmd,
                   {Binding::storageImage(atlas_, level + 1), Binding::storageImage(atlas_, level)},
                   push, engine::groupCount(push.size.x / 2, ISM_IMAGE_GROUP),
                   engine::groupCount(push.size.y / 2, ISM_IMAGE_GROUP));
    engine::computeBarrier(cmd);
  }
}

void Ism::recordVisibility(VkCommandBuffer cmd, const engine::GBuffer& gbuffer,
                           const engine::View& view, const engine::Buffer& vsgls,
                           uint32_t vsglIndex, engine::Image& out, engine::GpuProfiler* profiler) {
  using engine::Binding;
  if (vsglIndex >= maxVsgls_ || vsgls.size() < VkDeviceSize{vsglIndex + 1} * sizeof(gpu::Vsgl))
    throw engine::Error("ISM visibility: vsglIndex " + std::to_string(vsglIndex) +
                        " is outside the atlas or the VSGL buffer");
  if (out.desc().format != VK_FORMAT_R32_SFLOAT || out.desc().width != gbuffer.width ||
      out.desc().height != gbuffer.height)
    throw engine::Error("ISM visibility: the output is not an R32_SFLOAT image of the G-buffer's " +
                        std::to_string(gbuffer.width) + "x" + std::to_string(gbuffer.height));
  engine::ProfileScope scope(profiler, cmd, "ism visibility");
  if (out.layout() != VK_IMAGE_LAYOUT_GENERAL)
    engine::imageBarrier(cmd, out, VK_IMAGE_LAYOUT_GENERAL);
  gpu::IsmVisibilityPush push{};
  push.invViewProj = view.invViewProj;
  push.viewport = glm::uvec2(gbuffer.width, gbuffer.height);
  push.vsglIndex = vsglIndex;
  push.params = params();
  visibility_.dispatch(
      cmd,
      {Binding::storageImage(gbuffer.depth), Binding::storageImage(gbuffer.normal),
       Binding::storage(vsgls), Binding::storageImage(atlas_, 0), Binding::storageImage(out)},
      push, engine::groupCount(gbuffer.width, ISM_IMAGE_GROUP),
      engine::groupCount(gbuffer.height, ISM_IMAGE_GROUP));
  engine::computeBarrier(cmd);
}

}  // namespace gi
