#include "passes/brsm_pdf.h"

#include <bit>

#include "engine/commands.h"
#include "shared/brsm.h"
#include "spirv/brsm_compose.h"
#include "spirv/brsm_evaluate.h"

namespace gi {

namespace {

uint32_t log2Exact(uint32_t powerOfTwo) {
  return static_cast<uint32_t>(std::countr_zero(powerOfTwo));
}

}  // namespace

void validateBrsmSettings(const BrsmSettings& settings, uint32_t rsmSize) {
  if (settings.importanceCount < 1 || settings.importanceCount > kMaxImportanceCount)
    throw engine::Error("BRSM importanceCount " + std::to_string(settings.importanceCount) +
                        " is outside [1, " + std::to_string(kMaxImportanceCount) + "]");
  if (!std::has_single_bit(settings.gridSize) || settings.gridSize > rsmSize)
    throw engine::Error("BRSM gridSize " + std::to_string(settings.gridSize) +
                        " is not a power of two in [1, RSM size " + std::to_string(rsmSize) + "]");
  if (!(settings.fluxMix > 0.0f && settings.fluxMix <= 1.0f))
    throw engine::Error("BRSM fluxMix " + std::to_string(settings.fluxMix) + " is outside (0, 1]");
}

ImportanceVsgls::ImportanceVsgls(engine::Context& ctx, uint32_t width, uint32_t height,
                                 uint32_t maxCount)
    : flux_(ctx, "brsm camera flux"),
      vpls_(createVplImages(ctx, width, height)),
      attributes_(ctx, std::bit_ceil(std::max(width, height)), "brsm "),
      generator_(ctx, maxCount, "brsm ") {}

void ImportanceVsgls::record(VkCommandBuffer cmd, engine::GBuffer& gbuffer,
                             const engine::View& view, const VsglSettings& settings,
                             const MipPyramid& mips, engine::GpuProfiler* profiler, bool specular,
                             bool broadReflections) {
  if (view.width != vpls_.width || view.height != vpls_.height)
    throw engine::Error("BRSM importance: view " + std::to_string(view.width) + "x" +
                        std::to_string(view.height) + " differs from the " +
                        std::to_string(vpls_.width) + "x" + std::to_string(vpls_.height) +
                        " G-buffer it was created for");
  const RsmView importance = cameraImportanceView(view);
  // Unit emission without falloff: a pixel's weight is its reflectance times its solid angle.
  flux_.record(cmd, gbuffer, importance, FluxSource{}, vpls_, profiler);
  attributes_.record(cmd, vpls_, gbuffer, importance, mips, profiler, specular, broadReflections);
  generator_.record(cmd, attributes_, importance, settings, profiler);
}

BrsmPdf::BrsmPdf(engine::Context& ctx, uint32_t rsmSize, uint32_t gridSize)
    : rsmSize_(rsmSize),
      gridSize_(gridSize),
      compose_(ctx, "brsm_compose", kBrsmComposeSpv,
               std::vector<VkDescriptorType>(7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
               sizeof(gpu::BrsmComposePush)),
      cells_(createPyramid(ctx, gridSize)) {
  validateBrsmSettings({1, gridSize, 1.0f}, rsmSize);
  std::vector<VkDescriptorType> types(VSGL_ATTR_COUNT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  types.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  types.push_back(VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  for (uint32_t specular : {0u, 1u}) {
    const uint32_t specialization[] = {specular};
    evaluate_[specular] = engine::ComputeProgram(
        ctx, specular ? "brsm_evaluate" : "brsm_evaluate (diffuse lobes)", kBrsmEvaluateSpv, types,
        sizeof(gpu::BrsmEvaluatePush), specialization);
  }
}

void BrsmPdf::record(VkCommandBuffer cmd, VsglAttributes& light, const RsmView& view,
                     const engine::Buffer& importance, const BrsmSettings& settings,
                     const MipPyramid& mips, engine::GpuProfiler* profiler, bool specular) {
  validateBrsmSettings(settings, rsmSize_);
  if (settings.gridSize != gridSize_)
    throw engine::Error("BRSM gridSize " + std::to_string(settings.gridSize) +
                        " differs from the " + std::to_string(gridSize_) +
                        " it was created with (recreate to change it)");
  if (importance.size() < VkDeviceSize{settings.importanceCount} * sizeof(gpu::Vsgl))
    throw engine::Error("BRSM importanceCount " + std::to_string(settings.importanceCount) +
                        " exceeds the importance buffer");
  if (light.pyramid(0).desc().width != rsmSize_)
    throw engine::Error("BRSM: light pyramids are not " + std::to_string(rsmSize_) + "^2");
  using engine::Binding;
  const uint32_t level = log2Exact(rsmSize_ / gridSize_);
  const uint32_t rsmTop = log2Exact(rsmSize_);
  {
    engine::ProfileScope scope(profiler, cmd, "brsm evaluation");
    gpu::BrsmEvaluatePush push{};
    push.origin = glm::vec4(view.origin, 0.0f);
    push.importanceCount = settings.importanceCount;
    push.gridSize = gridSize_;
    evaluate_[specular].dispatch(cmd,
                                 {Binding::storageImage(light.pyramid(0), level),
                                  Binding::storageImage(light.pyramid(1), level),
                                  Binding::storageImage(light.pyramid(2), level),
                                  Binding::storageImage(light.pyramid(3), level),
                                  Binding::storageImage(light.pyramid(4), level),
                                  Binding::storageImage(light.pyramid(5), level),
                                  Binding::storage(importance), Binding::storageImage(cells_, 0)},
                                 push, engine::groupCount(gridSize_, BRSM_GROUP_X),
                                 engine::groupCount(gridSize_, BRSM_GROUP_Y));
    engine::computeBarrier(cmd);
  }
  engine::ProfileScope scope(profiler, cmd, "brsm pdf mipmapping");
  mips.record(cmd, cells_);
  gpu::BrsmComposePush push{rsmSize_, level, settings.fluxMix, 0};
  compose_.dispatch(
      cmd,
      {Binding::storageImage(light.pyramid(VSGL_ATTR_DIFFUSE_POWER), 0),
       Binding::storageImage(light.pyramid(VSGL_ATTR_SPECULAR_POWER), 0),
       Binding::storageImage(light.pyramid(VSGL_ATTR_DIFFUSE_POWER), rsmTop),
       Binding::storageImage(light.pyramid(VSGL_ATTR_SPECULAR_POWER), rsmTop),
       Binding::storageImage(cells_, 0), Binding::storageImage(cells_, log2Exact(gridSize_)),
       Binding::storageImage(light.pyramid(VSGL_ATTR_DIFFUSE_AXIS), 0)},
      push, engine::groupCount(rsmSize_, BRSM_GROUP_X), engine::groupCount(rsmSize_, BRSM_GROUP_Y));
  engine::computeBarrier(cmd);
  mips.record(cmd, light.pyramid(VSGL_ATTR_DIFFUSE_AXIS));
}

}  // namespace gi
