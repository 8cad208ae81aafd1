#include "passes/env_fis.h"

#include <string>

#include "engine/commands.h"
#include "engine/error.h"
#include "shared/env_fis.h"
#include "shared/environment.h"
#include "spirv/env_fis.h"

namespace gi {

EnvFisShade::EnvFisShade(engine::Context& ctx) : ctx_(&ctx) {}

void EnvFisShade::record(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
                         const Inputs& in, IndirectImages& out, engine::GpuProfiler* profiler) {
  if (!in.map || !in.sh || in.sampler == VK_NULL_HANDLE)
    throw engine::Error("environment FIS: missing map, sampler or SH buffer");
  const engine::ImageDesc& desc = in.map->desc();
  if (desc.layers != 2 || desc.width != in.mapSize || desc.height != in.mapSize ||
      desc.mips != in.levels || in.levels == 0)
    throw engine::Error("environment FIS: the map is not 2 layers of " +
                        std::to_string(in.mapSize) + "^2 with " + std::to_string(in.levels) +
                        " levels");
  if (in.sh->size() < sizeof(gpu::EnvSh))
    throw engine::Error("environment FIS: the SH buffer is smaller than gpu::EnvSh");
  if (in.sampleCount == 0 || in.sampleCount > 4096)
    throw engine::Error("environment FIS: " + std::to_string(in.sampleCount) +
                        " samples (1 to 4096)");
  const auto mode = static_cast<uint32_t>(in.mode), brdf = static_cast<uint32_t>(in.brdf);
  if (mode >= ENV_FIS_MODES || brdf >= ENV_FIS_BRDFS)
    throw engine::Error("environment FIS: unknown mode " + std::to_string(mode) + " or BRDF " +
                        std::to_string(brdf));
  std::optional<engine::ComputeProgram>& program = programs_[mode * ENV_FIS_BRDFS + brdf];
  if (!program) {
    const uint32_t specialization[] = {mode, brdf};
    program.emplace(
        *ctx_, "env_fis", kEnvFisSpv,
        std::vector<VkDescriptorType>{
            VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
            VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
            VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
            VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
        uint32_t(sizeof(gpu::EnvFisPush)), specialization);
  }
  engine::ProfileScope scope(profiler, cmd, "environment FIS");
  gpu::EnvFisPush push{};
  push.invViewProjRelative = engine::relativeUnprojection(camera).invViewProjRelative;
  push.viewport = {gbuffer.width, gbuffer.height};
  push.sampleCount = in.sampleCount;
  push.mapSize = in.mapSize;
  push.levelCount = in.levels;
  push.kernelExtent = in.kernelExtent;
  push.wardAnisotropy = in.wardAnisotropy;
  using engine::Binding;
  program->dispatch(
      cmd,
      {Binding::storageImage(gbuffer.depth), Binding::storageImage(gbuffer.normal),
       Binding::storageImage(gbuffer.diffuse), Binding::storageImage(gbuffer.specular),
       Binding::sampled(*in.map, in.sampler), Binding::storage(*in.sh),
       Binding::storageImage(out.diffuse), Binding::storageImage(out.glossy)},
      push, engine::groupCount(gbuffer.width, ENV_FIS_GROUP_X),
      engine::groupCount(gbuffer.height, ENV_FIS_GROUP_Y));
  engine::computeBarrier(cmd);
}

}  // namespace gi
