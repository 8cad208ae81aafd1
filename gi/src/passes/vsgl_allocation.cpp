#include "passes/vsgl_allocation.h"

#include <bit>

#include "engine/commands.h"
#include "engine/error.h"
#include "spirv/vsgl_allocate.h"
#include "spirv/vsgl_view_weight.h"

namespace gi {

namespace {

engine::Buffer viewBuffer(engine::Context& ctx, VkDeviceSize record) {
  return engine::Buffer(ctx, VkDeviceSize{VSGL_MAX_VIEWS} * record,
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                            VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        engine::MemoryUsage::GpuOnly);
}

}  // namespace

VsglAllocation::VsglAllocation(engine::Context& ctx)
    : weight_(ctx, "vsgl_view_weight", kVsglViewWeightSpv,
              {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
               VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
              sizeof(gpu::VsglViewWeightPush)),
      allocate_(ctx, "vsgl_allocate", kVsglAllocateSpv,
                {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                sizeof(gpu::VsglAllocatePush)),
      weights_(viewBuffer(ctx, sizeof(gpu::VsglViewWeight))),
      ranges_(viewBuffer(ctx, sizeof(gpu::VsglViewRange))) {}

void VsglAllocation::recordWeight(VkCommandBuffer cmd, uint32_t view, VsglAttributes& attributes,
                                  engine::Image* cells) {
  if (view >= VSGL_MAX_VIEWS)
    throw engine::Error("VSGL allocation: view " + std::to_string(view) + " past " +
                        std::to_string(VSGL_MAX_VIEWS));
  auto top = [](engine::Image& image) {
    return engine::Binding::storageImage(
        image, static_cast<uint32_t>(std::countr_zero(image.desc().width)));
  };
  engine::Image& diffuse = attributes.pyramid(VSGL_ATTR_DIFFUSE_POWER);
  gpu::VsglViewWeightPush push{};
  push.view = view;
  push.brsm = cells ? 1u : 0u;
  // Without the BRSM the cells binding is never read; the diffuse power stands in for it.
  weight_.dispatch(cmd,
                   {top(diffuse), top(attributes.pyramid(VSGL_ATTR_SPECULAR_POWER)),
                    top(cells ? *cells : diffuse), engine::Binding::storage(weights_)},
                   push, 1);
  engine::computeBarrier(cmd);
}

void VsglAllocation::recordAllocate(VkCommandBuffer cmd, uint32_t viewCount, uint32_t count,
                                    float fluxMix, engine::GpuProfiler* profiler) {
  if (viewCount < 1 || viewCount > VSGL_MAX_VIEWS)
    throw engine::Error("VSGL allocation: " + std::to_string(viewCount) + " views outside [1, " +
                        std::to_string(VSGL_MAX_VIEWS) + "]");
  engine::ProfileScope scope(profiler, cmd, "vsgl allocation");
  gpu::VsglAllocatePush push{};
  push.viewCount = viewCount;
  push.count = count;
  push.fluxMix = fluxMix;
  allocate_.dispatch(cmd, {engine::Binding::storage(weights_), engine::Binding::storage(ranges_)},
                     push, 1);
  engine::computeBarrier(cmd);
}

void VsglAllocation::recordRanges(VkCommandBuffer cmd, const std::vector<glm::uvec2>& ranges) {
  if (ranges.empty() || ranges.size() > VSGL_MAX_VIEWS)
    throw engine::Error("VSGL allocation: " + std::to_string(ranges.size()) + " views");
  std::vector<gpu::VsglViewRange> records(ranges.size());
  for (size_t v = 0; v < ranges.size(); ++v) records[v].range = glm::uvec4(ranges[v], 0u, 0u);
  engine::updateBuffer(cmd, ranges_, records.data(), records.size() * sizeof(gpu::VsglViewRange));
}

}  // namespace gi
