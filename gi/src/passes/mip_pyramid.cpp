#include "passes/mip_pyramid.h"

#include <bit>

#include "engine/commands.h"
#include "shared/mip_reduce.h"
#include "spirv/mip_reduce.h"

namespace gi {

engine::Image createPyramid(engine::Context& ctx, uint32_t size) {
  if (!std::has_single_bit(size))
    throw engine::Error("mip pyramid: size " + std::to_string(size) + " is not a power of two");
  engine::ImageDesc desc;
  desc.width = desc.height = size;
  desc.mips = static_cast<uint32_t>(std::bit_width(size));
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  engine::Image image(ctx, desc);
  engine::initialLayout(ctx, image, VK_IMAGE_LAYOUT_GENERAL);
  return image;
}

MipPyramid::MipPyramid(engine::Context& ctx)
    : program_(ctx, "mip_reduce", kMipReduceSpv,
               {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
               sizeof(gpu::MipReducePush)) {}

void MipPyramid::record(VkCommandBuffer cmd, engine::Image& image, engine::GpuProfiler* profiler,
                        const char* passName) const {
  record(cmd, image, glm::uvec2(image.desc().width, image.desc().height), profiler, passName);
}

void MipPyramid::record(VkCommandBuffer cmd, engine::Image& image, glm::uvec2 extent,
                        engine::GpuProfiler* profiler, const char* passName) const {
  engine::ProfileScope scope(profiler, cmd, passName);
  const engine::ImageDesc& desc = image.desc();
  if (extent.x > desc.width || extent.y > desc.height)
    throw engine::Error("mip pyramid: extent " + std::to_string(extent.x) + "x" +
                        std::to_string(extent.y) + " exceeds the " + std::to_string(desc.width) +
                        "^2 image");
  for (uint32_t level = 1; level < desc.mips; ++level) {
    // ceil(extent / 2^level): the texels with a child in the previous level's region.
    const glm::uvec2 size = glm::max((extent + (1u << level) - 1u) >> level, glm::uvec2(1u));
    gpu::MipReducePush push{size, 0, 0};
    program_.dispatch(cmd,
                      {engine::Binding::storageImage(image, level - 1),
                       engine::Binding::storageImage(image, level)},
                      push, engine::groupCount(size.x, MIP_GROUP_X),
                      engine::groupCount(size.y, MIP_GROUP_Y));
    engine::computeBarrier(cmd);
  }
}

}  // namespace gi
