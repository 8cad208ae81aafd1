#include "passes/adaptive_shading.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/commands.h"
#include "engine/error.h"
#include "spirv/adaptive_decide.h"

namespace gi {

gpu::AdaptiveDecidePush adaptiveDecidePush(const AdaptiveSettings& settings,
                                           const engine::View& camera, uint32_t width,
                                           uint32_t height, uint32_t level, bool splitGlossy) {
  gpu::AdaptiveDecidePush push{};
  push.invViewProjRelative = engine::relativeUnprojection(camera).invViewProjRelative;
  push.viewport = {width, height};
  push.level = level;
  push.coarsest = settings.coarsestLevel;
  push.planeTolerance = settings.planeTolerance;
  push.normalCosine = std::cos(settings.normalAngle);
  push.roughnessTolerance = settings.roughnessTolerance;
  push.f0Tolerance = settings.f0Tolerance;
  push.lightTolerance = settings.lightTolerance;
  push.splitGlossy = splitGlossy ? 1u : 0u;
  return push;
}

namespace {

// A level's queue: its header, then an entry per texel and, for ordered queues, the padding of
// each decide group (below ADAPTIVE_QUEUE_GROUP: orderedAlign is a subgroup size that divides it).
engine::Buffer queueBuffer(engine::Context& ctx, uint32_t width, uint32_t height, uint32_t level) {
  const uint32_t w = gpu::adaptiveLevelSize(width, level),
                 h = gpu::adaptiveLevelSize(height, level);
  const VkDeviceSize groups = VkDeviceSize{engine::groupCount(w, ADAPTIVE_GROUP_X)} *
                              engine::groupCount(h, ADAPTIVE_GROUP_Y);
  const VkDeviceSize entries = VkDeviceSize{w} * h + groups * (ADAPTIVE_QUEUE_GROUP - 1);
  return engine::Buffer(ctx, sizeof(gpu::AdaptiveQueueHeader) + 4 * entries,
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        engine::MemoryUsage::GpuOnly);
}

// The largest subgroup size a compute pipeline may run with (Vulkan 1.3): ordered queues pad to
// it, so that subgroups of any size that divides it start at a range's start.
uint32_t largestSubgroupSize(engine::Context& ctx) {
  VkPhysicalDeviceVulkan13Properties v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES,
                                              &v13};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
  vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
  const uint32_t largest = std::max(subgroup.subgroupSize, v13.maxSubgroupSize);
  if (largest == 0 || ADAPTIVE_QUEUE_GROUP % largest != 0)
    throw engine::Error("adaptive shading: subgroup size " + std::to_string(largest) +
                        " does not divide the queue group of " +
                        std::to_string(ADAPTIVE_QUEUE_GROUP));
  return largest;
}

}  // namespace

AdaptiveShading::AdaptiveShading(engine::Context& ctx, uint32_t width, uint32_t height)
    : ctx_(&ctx),
      subgroupAlign_(largestSubgroupSize(ctx)),
      width_(width),
      height_(height),
      decide_(ctx, "adaptive_decide", kAdaptiveDecideSpv,
              std::vector<VkDescriptorType>{
                  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                  VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                  VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
              uint32_t(sizeof(gpu::AdaptiveDecidePush))),
      counts_(ctx, 2 * sizeof(gpu::AdaptiveQueueHeader) * (ADAPTIVE_MAX_LEVEL + 1),
              VK_BUFFER_USAGE_TRANSFER_DST_BIT, engine::MemoryUsage::Readback) {
  for (uint32_t level = 1; level <= ADAPTIVE_MAX_LEVEL; ++level)
    levels_.push_back(createIndirectImages(ctx, gpu::adaptiveLevelSize(width, level),
                                           gpu::adaptiveLevelSize(height, level)));
  for (uint32_t level = 0; level <= ADAPTIVE_MAX_LEVEL; ++level)
    queues_.push_back(
        {queueBuffer(ctx, width, height, level), queueBuffer(ctx, width, height, level)});
  std::memset(counts_.mapped(), 0, counts_.size());
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  levelMap_ = engine::Image(ctx, desc);
  engine::initialLayout(ctx, levelMap_, VK_IMAGE_LAYOUT_GENERAL);
}

void AdaptiveShading::record(VkCommandBuffer cmd, engine::GBuffer& gbuffer,
                             const engine::View& camera, const VsglShade::Inputs& in,
                             const AdaptiveSettings& settings, bool splitGlossy, VsglShade& shade,
                             IndirectImages& out, engine::GpuProfiler* profiler) {
  engine::ProfileScope scope(profiler, cmd, "vsgl shading");
  const uint32_t coarsest = settings.coarsestLevel;
  // Empty queues whose indirect dispatch has 0 x 1 x 1 groups.
  gpu::AdaptiveQueueHeader empty{};
  empty.groupsY = empty.groupsZ = 1;
  for (uint32_t level = 0; level <= coarsest; ++level)
    for (const engine::Buffer* queue : {&queues_[level].glossy, &queues_[level].plain})
      engine::updateBuffer(cmd, *queue, &empty, sizeof(empty));
  using engine::Binding;
  for (uint32_t level = coarsest + 1; level-- > 0;) {
    IndirectImages& target = level == 0 ? out : levels_[level - 1];
    // The parents: level + 1, or at the coarsest level (never read) the level's own images.
    IndirectImages& parent = level < coarsest ? levels_[level] : target;
    gpu::AdaptiveDecidePush push =
        adaptiveDecidePush(settings, camera, width_, height_, level, splitGlossy);
    // VSGL culling decides per subgroup of the queue: its texels must be the same every run.
    if (in.flags & VSGL_SHADE_CULL) push.orderedAlign = subgroupAlign_;
    {
      engine::ProfileScope decideScope(profiler, cmd, "adaptive decide L" + std::to_string(level));
      decide_.dispatch(
          cmd,
          {Binding::storageImage(gbuffer.depth), Binding::storageImage(gbuffer.normal),
           Binding::storageImage(gbuffer.diffuse), Binding::storageImage(gbuffer.specular),
           Binding::storageImage(parent.diffuse), Binding::storageImage(parent.glossy),
           Binding::storageImage(target.diffuse), Binding::storageImage(target.glossy),
           Binding::storage(queues_[level].glossy), Binding::storageImage(levelMap_),
           Binding::storage(queues_[level].plain)},
          push, engine::groupCount(gpu::adaptiveLevelSize(width_, level), ADAPTIVE_GROUP_X),
          engine::groupCount(gpu::adaptiveLevelSize(height_, level), ADAPTIVE_GROUP_Y));
      engine::computeBarrier(cmd);
    }
    VsglShade::Inputs queued = in;
    queued.flags |= VSGL_SHADE_QUEUE;
    queued.queue = &queues_[level].glossy;
    queued.level = level;
    shade.record(cmd, gbuffer, camera, queued, target, profiler);
    if (splitGlossy) {  // the same level's texels without a glossy term, by the variant without it
      queued.flags &= ~VSGL_SHADE_GLOSSY;
      queued.queue = &queues_[level].plain;
      shade.record(cmd, gbuffer, camera, queued, target, profiler);
    }
  }
  // The heads, for lastCounts() once the frame has completed.
  engine::computeToTransferBarrier(cmd);
  for (uint32_t level = 0; level <= ADAPTIVE_MAX_LEVEL; ++level)
    for (uint32_t plain = 0; plain < 2; ++plain) {
      const VkBufferCopy copy{0, (2 * level + plain) * sizeof(gpu::AdaptiveQueueHeader),
                              sizeof(gpu::AdaptiveQueueHeader)};
      const engine::Buffer& queue = plain ? queues_[level].plain : queues_[level].glossy;
      if (level <= coarsest)
        vkCmdCopyBuffer(cmd, queue.handle(), counts_.handle(), 1, &copy);
      else
        vkCmdFillBuffer(cmd, counts_.handle(), copy.dstOffset, copy.size, 0);
    }
  engine::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_HOST_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                        VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

ShadingCounts AdaptiveShading::lastCounts() const {
  // Per level: the glossy queue's head (which also counts interpolation, reuse and the sky),
  // then the plain queue's.
  std::array<gpu::AdaptiveQueueHeader, 2 * (ADAPTIVE_MAX_LEVEL + 1)> heads;
  std::memcpy(heads.data(), counts_.mapped(), sizeof(heads));
  ShadingCounts c;
  c.adaptive = true;
  for (uint32_t level = 0; level <= ADAPTIVE_MAX_LEVEL; ++level) {
    const gpu::AdaptiveQueueHeader &glossy = heads[2 * level], &plain = heads[2 * level + 1];
    c.shaded[level] = glossy.shaded + plain.shaded;
    c.shadedWithoutGlossy[level] = plain.shaded;
    c.interpolated[level] = glossy.interpolated;
    c.reused[level] = glossy.reused;
    c.pixelsFrom[level] = heads[0].fromLevel[level];
  }
  c.pixelsFrom[0] += c.shaded[0];
  c.skyPixels = heads[0].sky;
  return c;
}

}  // namespace gi
