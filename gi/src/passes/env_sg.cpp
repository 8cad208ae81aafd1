#include "passes/env_sg.h"

#include <bit>
#include <numbers>
#include <string>
#include <vector>

#include "engine/commands.h"
#include "engine/error.h"
#include "common/env_texels.h"
#include "passes/ggx_albedo_table.h"
#include "shared/env_map.h"
#include "spirv/env_mip_reduce.h"
#include "spirv/env_sg_generate.h"
#include "spirv/env_sg_pyramid.h"
#include "spirv/env_sg_shade.h"

namespace gi {

namespace {

constexpr uint32_t kLayers = 2;
constexpr uint32_t kMaxSize = 4096;

}  // namespace

EnvSgLights::EnvSgLights(engine::Context& ctx, uint32_t mapSize, uint32_t maxCount)
    : size_(mapSize), maxCount_(maxCount) {
  if (mapSize == 0 || mapSize > kMaxSize || !std::has_single_bit(mapSize))
    throw engine::Error("environment SG lights: map size " + std::to_string(mapSize) +
                        " is not a power of two in [1, " + std::to_string(kMaxSize) + "]");
  if (maxCount == 0) throw engine::Error("environment SG lights: a maximum of 0 lights");
  solidAngleScale_ = float(4.0 * std::numbers::pi / envSgOwnSolidAngle(mapSize));
  engine::ImageDesc desc;
  desc.width = desc.height = mapSize;
  desc.layers = kLayers;
  desc.mips = static_cast<uint32_t>(std::bit_width(mapSize));
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  desc.arrayView = true;
  for (engine::Image& pyramid : pyramids_) {
    pyramid = engine::Image(ctx, desc);
    engine::initialLayout(ctx, pyramid, VK_IMAGE_LAYOUT_GENERAL);
  }
  sampler_ = engine::Sampler(ctx, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  lights_ = engine::Buffer(ctx, VkDeviceSize{maxCount} * sizeof(gpu::EnvSgLight),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  albedoTable_ = createGgxAlbedoTable(ctx);

  using Type = std::vector<VkDescriptorType>;
  constexpr VkDescriptorType kStorageImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  constexpr VkDescriptorType kStorageBuffer = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  build_ = engine::ComputeProgram(ctx, "env_sg_pyramid", kEnvSgPyramidSpv,
                                  Type{kStorageImage, kStorageImage, kStorageImage},
                                  sizeof(gpu::EnvSgPyramidPush));
  mips_ = engine::ComputeProgram(ctx, "env_mip_reduce", kEnvMipReduceSpv,
                                 Type{kStorageImage, kStorageImage}, sizeof(gpu::EnvMipPush));
  generate_ = engine::ComputeProgram(ctx, "env_sg_generate", kEnvSgGenerateSpv,
                                     Type{kSampled, kSampled, kStorageBuffer},
                                     sizeof(gpu::EnvSgGeneratePush));
  shade_ =
      engine::ComputeProgram(ctx, "env_sg_shade", kEnvSgShadeSpv,
                             Type{kStorageImage, kStorageImage, kStorageImage, kStorageImage,
                                  kStorageBuffer, kStorageImage, kStorageImage, kStorageBuffer},
                             sizeof(gpu::EnvSgShadePush));
}

void EnvSgLights::record(VkCommandBuffer cmd, const EnvironmentMap& environment, uint32_t count,
                         float kernelScale, engine::GpuProfiler* profiler) {
  if (environment.size() != size_)
    throw engine::Error("environment SG lights: a map of size " +
                        std::to_string(environment.size()) + " for pyramids of size " +
                        std::to_string(size_));
  if (count < 1 || count > maxCount_)
    throw engine::Error("environment SG lights: " + std::to_string(count) + " lights outside [1, " +
                        std::to_string(maxCount_) + "]");
  if (!(kernelScale >= 1.0f) || kernelScale > float(count))
    throw engine::Error("environment SG lights: kernel scale K = " + std::to_string(kernelScale) +
                        " outside [1, N = " + std::to_string(count) + "]");
  const uint32_t levels = pyramids_[0].desc().mips;
  {
    engine::ProfileScope scope(profiler, cmd, "environment SG pyramids");
    const gpu::EnvSgPyramidPush push{size_, 0, 0, 0};
    build_.dispatch(cmd,
                    {engine::Binding::storageImage(environment.map(), 0),
                     engine::Binding::storageImage(pyramids_[ENV_SG_RADIANCE], 0),
                     engine::Binding::storageImage(pyramids_[ENV_SG_DIRECTION], 0)},
                    push, engine::groupCount(size_, ENV_SG_PYRAMID_GROUP_X),
                    engine::groupCount(size_, ENV_SG_PYRAMID_GROUP_Y), kLayers);
    engine::computeBarrier(cmd);
    for (uint32_t level = 1; level < levels; ++level) {
      const uint32_t n = size_ >> level;
      const gpu::EnvMipPush mipPush{{n, n}, 0, 0};
      for (engine::Image& pyramid : pyramids_)
        mips_.dispatch(cmd,
                       {engine::Binding::storageImage(pyramid, level - 1),
                        engine::Binding::storageImage(pyramid, level)},
                       mipPush, engine::groupCount(n, ENV_MIP_GROUP_X),
                       engine::groupCount(n, ENV_MIP_GROUP_Y), kLayers);
      engine::computeBarrier(cmd);
    }
  }
  {
    engine::ProfileScope scope(profiler, cmd, "environment SG generation");
    gpu::EnvSgGeneratePush push{};
    push.count = count;
    push.size = size_;
    push.topLevel = levels - 1;
    push.kernelScale = kernelScale;
    push.solidAngleScale = solidAngleScale_;
    const VkSampler s = sampler_.handle();
    generate_.dispatch(cmd,
                       {engine::Binding::sampled(pyramids_[ENV_SG_RADIANCE], s),
                        engine::Binding::sampled(pyramids_[ENV_SG_DIRECTION], s),
                        engine::Binding::storage(lights_)},
                       push, engine::groupCount(count, ENV_SG_GENERATE_GROUP));
    engine::computeBarrier(cmd);
  }
  count_ = count;
}

void EnvSgLights::shade(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
                        IndirectImages& out, engine::GpuProfiler* profiler) {
  if (count_ == 0) throw engine::Error("environment SG lights: shade() before any record()");
  engine::ProfileScope scope(profiler, cmd, "environment SG shading");
  gpu::EnvSgShadePush push{};
  push.invViewProjRelative = engine::relativeUnprojection(camera).invViewProjRelative;
  push.viewport = {gbuffer.width, gbuffer.height};
  push.count = count_;
  using engine::Binding;
  shade_.dispatch(cmd,
                  {Binding::storageImage(gbuffer.depth), Binding::storageImage(gbuffer.normal),
                   Binding::storageImage(gbuffer.diffuse), Binding::storageImage(gbuffer.specular),
                   Binding::storage(lights_), Binding::storageImage(out.diffuse),
                   Binding::storageImage(out.glossy), Binding::storage(albedoTable_)},
                  push, engine::groupCount(gbuffer.width, ENV_SG_SHADE_GROUP_X),
                  engine::groupCount(gbuffer.height, ENV_SG_SHADE_GROUP_Y));
  engine::computeBarrier(cmd);
}

}  // namespace gi
