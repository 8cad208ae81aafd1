#include "passes/gbuffer_convert.h"

#include "engine/commands.h"
#include "spirv/gbuffer_convert.h"

namespace gi {
namespace {

engine::Image storageImage(engine::Context& ctx, uint32_t width, uint32_t height, VkFormat format) {
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  engine::Image image(ctx, desc);
  engine::initialLayout(ctx, image, VK_IMAGE_LAYOUT_GENERAL);
  return image;
}

}  // namespace

GBufferConvert::GBufferConvert(engine::Context& ctx, uint32_t width, uint32_t height)
    : program_(ctx, "gbuffer_convert", kGbufferConvertSpv,
               {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
               sizeof(gpu::GBufferConvertPush)),
      sampler_(ctx, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, VK_FILTER_NEAREST),
      depth_(storageImage(ctx, width, height, VK_FORMAT_R32_SFLOAT)),
      normal_(storageImage(ctx, width, height, VK_FORMAT_R16G16_SNORM)) {}

void GBufferConvert::record(VkCommandBuffer cmd, const engine::Image& hostDepth,
                            const engine::Image& hostNormal, const gpu::GBufferConvertPush& push,
                            engine::GpuProfiler* profiler) {
  using engine::Binding;
  engine::ProfileScope scope(profiler, cmd, "gbuffer convert");
  program_.dispatch(cmd,
                    {Binding::sampled(hostDepth, sampler_.handle()),
                     Binding::sampled(hostNormal, sampler_.handle()),
                     Binding::storageImage(depth_), Binding::storageImage(normal_)},
                    push, engine::groupCount(push.viewport.x, GBUFFER_CONVERT_GROUP),
                    engine::groupCount(push.viewport.y, GBUFFER_CONVERT_GROUP));
  engine::computeBarrier(cmd);
}

}  // namespace gi
