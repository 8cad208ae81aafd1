#include "passes/env_map.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/commands.h"
#include "shared/env_map.h"
#include "shared/environment.h"
#include "spirv/env_mip_reduce.h"
#include "spirv/env_paraboloid.h"
#include "spirv/env_sh.h"

namespace gi {

namespace {

constexpr uint32_t kLayers = 2;
constexpr uint32_t kMaxSize = 4096;

void checkFormat(engine::Context& ctx) {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), VK_FORMAT_R32G32B32A32_SFLOAT,
                                      &properties);
  const VkFormatFeatureFlags features = properties.optimalTilingFeatures;
  if (!(features & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    throw engine::Error(
        "environment map: the device cannot filter R32G32B32A32_SFLOAT images linearly "
        "(VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT), which the trilinear environment "
        "lookups need");
  if (!(features & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
    throw engine::Error(
        "environment map: the device cannot use R32G32B32A32_SFLOAT as a storage image "
        "(VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT)");
}

}  // namespace

EnvironmentMap::EnvironmentMap(engine::Context& ctx, uint32_t size) : size_(size) {
  if (size == 0 || size > kMaxSize || !std::has_single_bit(size))
    throw engine::Error("environment map: size " + std::to_string(size) +
                        " is not a power of two in [1, " + std::to_string(kMaxSize) + "]");
  checkFormat(ctx);
  maxImageDimension_ = ctx.properties().limits.maxImageDimension2D;
  const uint32_t levelCount = static_cast<uint32_t>(std::bit_width(size));
  shLevel_ = size > ENV_SH_LEVEL_SIZE
                 ? levelCount - static_cast<uint32_t>(std::bit_width(uint32_t{ENV_SH_LEVEL_SIZE}))
                 : 0u;

  engine::ImageDesc desc;
  desc.width = desc.height = size;
  desc.layers = kLayers;
  desc.mips = levelCount;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  desc.arrayView = true;
  map_ = engine::Image(ctx, desc);
  engine::initialLayout(ctx, map_, VK_IMAGE_LAYOUT_GENERAL);
  sampler_ = engine::Sampler(ctx, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  sh_ = engine::Buffer(ctx, sizeof(gpu::EnvSh),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       engine::MemoryUsage::GpuOnly);

  convert_ = engine::ComputeProgram(
      ctx, "env_paraboloid", kEnvParaboloidSpv,
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
      sizeof(gpu::EnvConvertPush));
  mips_ =
      engine::ComputeProgram(ctx, "env_mip_reduce", kEnvMipReduceSpv,
                             {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                             sizeof(gpu::EnvMipPush));
  project_ =
      engine::ComputeProgram(ctx, "env_sh", kEnvShSpv,
                             {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                             sizeof(gpu::EnvShPush));
}

void EnvironmentMap::upload(engine::Context& ctx, const engine::ImageRgba32f& equirect) {
  const std::string what = "environment image";
  if (equirect.width <= 0 || equirect.height <= 0)
    throw engine::Error(what + ": empty (" + std::to_string(equirect.width) + " x " +
                        std::to_string(equirect.height) + " pixels)");
  const size_t pixels = size_t(equirect.width) * size_t(equirect.height);
  if (equirect.pixels.size() != pixels * 4)
    throw engine::Error(what + ": " + std::to_string(equirect.pixels.size()) + " floats for " +
                        std::to_string(equirect.width) + " x " + std::to_string(equirect.height) +
                        " RGBA pixels (expected " + std::to_string(pixels * 4) + ")");
  if (uint32_t(equirect.width) > maxImageDimension_ ||
      uint32_t(equirect.height) > maxImageDimension_)
    throw engine::Error(
        what + ": " + std::to_string(equirect.width) + " x " + std::to_string(equirect.height) +
        " pixels exceed the device's image limit of " + std::to_string(maxImageDimension_));
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c) {
      const float value = equirect.pixels[i * 4 + c];
      if (std::isfinite(value) && value >= 0.0f) continue;
      const size_t x = i % size_t(equirect.width), y = i / size_t(equirect.width);
      throw engine::Error(what + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                          ") channel " + "rgb"[c] + " is " +
                          (std::isnan(value)   ? std::string("NaN")
                           : std::isinf(value) ? std::string("infinite")
                                               : "negative (" + std::to_string(value) + ")") +
                          "; radiance must be finite and non-negative");
    }

  engine::ImageDesc desc;
  desc.width = uint32_t(equirect.width);
  desc.height = uint32_t(equirect.height);
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  const size_t bytes = equirect.pixels.size() * sizeof(float);
  engine::Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, engine::MemoryUsage::Upload);
  std::memcpy(staging.mapped(), equirect.pixels.data(), bytes);
  equirect_ = engine::Image(ctx, desc);
  staging_ = std::move(staging);
  pending_ = true;
}

void EnvironmentMap::record(VkCommandBuffer cmd, engine::GpuProfiler* profiler) {
  if (!hasEnvironment()) throw engine::Error("environment map: record() before any upload()");
  if (pending_) {
    engine::imageBarrier(cmd, equirect_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {equirect_.desc().width, equirect_.desc().height, 1};
    vkCmdCopyBufferToImage(cmd, staging_.handle(), equirect_.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    engine::imageBarrier(cmd, equirect_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    pending_ = false;
  }
  {
    engine::ProfileScope scope(profiler, cmd, "environment conversion");
    const gpu::EnvConvertPush push{{equirect_.desc().width, equirect_.desc().height}, size_, 0};
    convert_.dispatch(cmd,
                      {engine::Binding::sampled(equirect_, sampler_.handle()),
                       engine::Binding::storageImage(map_, 0)},
                      push, engine::groupCount(size_, ENV_CONVERT_GROUP_X),
                      engine::groupCount(size_, ENV_CONVERT_GROUP_Y), kLayers);
    engine::computeBarrier(cmd);
  }
  {
    engine::ProfileScope scope(profiler, cmd, "environment mipmapping");
    for (uint32_t level = 1; level < levels(); ++level) {
      const uint32_t n = size_ >> level;
      const gpu::EnvMipPush push{{n, n}, 0, 0};
      mips_.dispatch(cmd,
                     {engine::Binding::storageImage(map_, level - 1),
                      engine::Binding::storageImage(map_, level)},
                     push, engine::groupCount(n, ENV_MIP_GROUP_X),
                     engine::groupCount(n, ENV_MIP_GROUP_Y), kLayers);
      engine::computeBarrier(cmd);
    }
  }
  {
    engine::ProfileScope scope(profiler, cmd, "environment SH");
    const gpu::EnvShPush push{size_ >> shLevel_, 0, 0, 0};
    project_.dispatch(
        cmd, {engine::Binding::storageImage(map_, shLevel_), engine::Binding::storage(sh_)}, push,
        1);
    engine::computeBarrier(cmd);
  }
}

}  // namespace gi
