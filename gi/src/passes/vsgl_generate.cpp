#include "passes/vsgl_generate.h"

#include <algorithm>
#include <bit>

#include "engine/commands.h"
#include "shared/vsgl_allocation.h"
#include "shared/vsgl_generate.h"
#include "spirv/vsgl_generate.h"

namespace gi {

VsglGenerator::VsglGenerator(engine::Context& ctx, uint32_t maxCount, std::string passPrefix)
    : maxCount_(maxCount),
      passPrefix_(std::move(passPrefix)),
      program_(
          ctx, "vsgl_generate", kVsglGenerateSpv,
          [] {
            std::vector<VkDescriptorType> types(VSGL_ATTR_COUNT,
                                                VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
            types.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
            types.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
            return types;
          }(),
          sizeof(gpu::VsglGeneratePush)),
      sampler_(ctx, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
      vsgls_(ctx, VkDeviceSize{maxCount} * sizeof(gpu::Vsgl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
             engine::MemoryUsage::GpuOnly),
      noRanges_(ctx, sizeof(gpu::VsglViewRange), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                engine::MemoryUsage::GpuOnly) {}

void VsglGenerator::record(VkCommandBuffer cmd, VsglAttributes& attributes, const RsmView& view,
                           const VsglSettings& settings, engine::GpuProfiler* profiler) {
  dispatch(cmd, attributes, view, settings, nullptr, 0, profiler);
}

void VsglGenerator::recordRanged(VkCommandBuffer cmd, VsglAttributes& attributes,
                                 const RsmView& view, const VsglSettings& settings,
                                 const engine::Buffer& ranges, uint32_t rangeIndex,
                                 engine::GpuProfiler* profiler) {
  VsglSettings bound = settings;
  bound.first = 0;
  dispatch(cmd, attributes, view, bound, &ranges, rangeIndex, profiler);
}

void VsglGenerator::dispatch(VkCommandBuffer cmd, VsglAttributes& attributes, const RsmView& view,
                             const VsglSettings& settings, const engine::Buffer* ranges,
                             uint32_t rangeIndex, engine::GpuProfiler* profiler) {
  if (settings.count < 1 || settings.count > maxCount_ - std::min(settings.first, maxCount_))
    throw engine::Error("VSGL count " + std::to_string(settings.count) + " from record " +
                        std::to_string(settings.first) + " outside [1, " +
                        std::to_string(maxCount_) + "]");
  if (!(settings.kernelScale >= 1.0f))
    throw engine::Error("VSGL kernel scale K = " + std::to_string(settings.kernelScale) +
                        " must be >= 1");
  if (!(settings.surfaceTolerance >= 0.0f))
    throw engine::Error("VSGL surface tolerance " + std::to_string(settings.surfaceTolerance) +
                        " must be >= 0");
  if (settings.rule > VSGL_RULE_POINT)
    throw engine::Error("VSGL rule " + std::to_string(settings.rule) +
                        " is none of Tok15, modified FIS and VPLs");
  const bool point = settings.rule == VSGL_RULE_POINT;
  engine::ProfileScope scope(profiler, cmd,
                             passPrefix_ + (point ? "vpl sampling" : "filtered sampling"));
  const uint32_t size = attributes.pyramid(0).desc().width;
  gpu::VsglGeneratePush push{};
  push.origin = glm::vec4(view.origin, 0.0f);
  push.count = settings.count;
  push.rule = settings.rule;
  push.size = size;
  push.topLevel = static_cast<uint32_t>(std::countr_zero(size));
  push.kernelScale = settings.kernelScale;
  push.texelPatch = glm::vec4(view.axis, view.texelArea);
  push.perspective = view.perspective ? 1u : 0u;
  push.ranged = ranges ? 1u : 0u;
  push.view = rangeIndex;
  push.surfaceTolerance = point ? 0.0f : settings.surfaceTolerance;
  using engine::Binding;
  VkSampler s = sampler_.handle();
  program_.dispatch(
      cmd,
      {Binding::sampled(attributes.pyramid(0), s), Binding::sampled(attributes.pyramid(1), s),
       Binding::sampled(attributes.pyramid(2), s), Binding::sampled(attributes.pyramid(3), s),
       Binding::sampled(attributes.pyramid(4), s), Binding::sampled(attributes.pyramid(5), s),
       ranges ? Binding::storage(vsgls_)
              : Binding::storage(vsgls_, VkDeviceSize{settings.first} * sizeof(gpu::Vsgl),
                                 VkDeviceSize{settings.count} * sizeof(gpu::Vsgl)),
       Binding::storage(ranges ? *ranges : noRanges_)},
      push, engine::groupCount(settings.count, VSGL_GENERATE_GROUP));
  engine::computeBarrier(cmd);
}

}  // namespace gi
