#include "passes/vsgl_shade.h"

#include <cstring>

#include "engine/commands.h"
#include "passes/ggx_albedo_table.h"
#include "shared/adaptive_shading.h"
#include "shared/vsgl.h"
#include "shared/vsgl_shade.h"
#include "spirv/vpl_shade.h"
#include "spirv/vsgl_shade.h"

namespace gi {

IndirectImages createIndirectImages(engine::Context& ctx, uint32_t width, uint32_t height) {
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  // Transfer destination: the planner clears them when no light can bounce.
  desc.usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  IndirectImages images{engine::Image(ctx, desc), engine::Image(ctx, desc)};
  engine::initialLayout(ctx, images.diffuse, VK_IMAGE_LAYOUT_GENERAL);
  engine::initialLayout(ctx, images.glossy, VK_IMAGE_LAYOUT_GENERAL);
  return images;
}

VsglShade::VsglShade(engine::Context& ctx)
    : ctx_(&ctx),
      albedoTable_(createGgxAlbedoTable(ctx)),
      noQueue_(ctx, sizeof(gpu::AdaptiveQueueHeader) + sizeof(uint32_t),
               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly),
      stats_(ctx, sizeof(gpu::VsglShadeStats),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT,
             engine::MemoryUsage::GpuOnly),
      statsReadback_(ctx, sizeof(gpu::VsglShadeStats), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     engine::MemoryUsage::Readback) {
  std::memset(statsReadback_.mapped(), 0, statsReadback_.size());
}

void VsglShade::record(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
                       const Inputs& in, IndirectImages& out, engine::GpuProfiler* profiler) {
  if (in.vsgls->size() < VkDeviceSize{in.vsglCount} * sizeof(gpu::Vsgl))
    throw engine::Error("VSGL shading: " + std::to_string(in.vsglCount) +
                        " VSGLs exceed the VSGL buffer");
  if (in.flags >= VSGL_SHADE_VARIANTS)
    throw engine::Error("VSGL shading: unknown flags " + std::to_string(in.flags));
  const bool queued = (in.flags & VSGL_SHADE_QUEUE) != 0;
  if (queued && !in.queue) throw engine::Error("VSGL shading: a queued variant without a queue");
  if (in.points && (in.flags & (VSGL_SHADE_QUEUE | VSGL_SHADE_CULL)))
    throw engine::Error("VPL shading: neither adaptive queues nor culling apply to point lights");
  // vpl_shade.comp's emitters are always planar: one variant serves both values of the flag.
  const uint32_t variant = in.points ? in.flags & ~VSGL_SHADE_PLANAR : in.flags;
  if (in.ism.pcf > ISM_MAX_PCF)
    throw engine::Error("VSGL shading: unknown ISM filter " + std::to_string(in.ism.pcf));
  std::optional<engine::ComputeProgram>& program = programs_[in.points][in.ism.pcf][variant];
  if (!program) {
    const uint32_t specialization[] = {variant, in.ism.pcf};
    const std::span<const uint32_t> spirv = in.points ? std::span<const uint32_t>(kVplShadeSpv)
                                                      : std::span<const uint32_t>(kVsglShadeSpv);
    program.emplace(*ctx_, in.points ? "vpl_shade" : "vsgl_shade", spirv,
                    std::vector<VkDescriptorType>{
                        VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                        VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                        VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                    uint32_t(sizeof(gpu::VsglShadePush)), specialization);
  }
  engine::ProfileScope scope(profiler, cmd,
                             in.points ? "vpl shading"
                             : queued  ? "vsgl shading L" + std::to_string(in.level)
                                       : "vsgl shading");
  using engine::Binding;
  gpu::VsglShadePush push{};
  const engine::RelativeUnprojection unprojection = engine::relativeUnprojection(camera);
  push.invViewProjRelative = unprojection.invViewProjRelative;
  push.eye = unprojection.eye;
  push.cullBudget = in.cullBudget;
  push.viewport = {gbuffer.width, gbuffer.height};
  push.vsglCount = in.vsglCount;
  push.ism = in.ism;
  push.level = in.level;
  const engine::Buffer& queue = queued ? *in.queue : noQueue_;
  const std::initializer_list<Binding> bindings = {Binding::storageImage(gbuffer.depth),
                                                   Binding::storageImage(gbuffer.normal),
                                                   Binding::storageImage(gbuffer.diffuse),
                                                   Binding::storageImage(gbuffer.specular),
                                                   Binding::storage(*in.vsgls),
                                                   Binding::storageImage(out.diffuse),
                                                   Binding::storageImage(out.glossy),
                                                   Binding::storageImage(*in.ismAtlas, 0),
                                                   Binding::storage(albedoTable_),
                                                   Binding::storage(queue),
                                                   Binding::storage(stats_)};
  if (queued)
    program->dispatchIndirect(cmd, bindings, push, queue, 0);
  else
    program->dispatch(cmd, bindings, push, engine::groupCount(gbuffer.width, VSGL_SHADE_GROUP_X),
                      engine::groupCount(gbuffer.height, VSGL_SHADE_GROUP_Y));
  engine::computeBarrier(cmd);
}

void VsglShade::recordStatsReset(VkCommandBuffer cmd) {
  engine::fillBuffer(cmd, stats_, 0);
}

void VsglShade::recordStatsReadback(VkCommandBuffer cmd) {
  engine::computeToTransferBarrier(cmd);
  const VkBufferCopy copy{0, 0, sizeof(gpu::VsglShadeStats)};
  vkCmdCopyBuffer(cmd, stats_.handle(), statsReadback_.handle(), 1, &copy);
  engine::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

gpu::VsglShadeStats VsglShade::lastStats() const {
  gpu::VsglShadeStats stats;
  std::memcpy(&stats, statsReadback_.mapped(), sizeof(stats));
  return stats;
}

}  // namespace gi
