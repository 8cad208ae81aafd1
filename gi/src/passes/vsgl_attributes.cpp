#include "passes/vsgl_attributes.h"

#include "engine/commands.h"
#include "shared/vsgl_attributes_pass.h"
#include "spirv/vsgl_attributes.h"

namespace gi {

VsglAttributes::VsglAttributes(engine::Context& ctx, uint32_t size, std::string passPrefix)
    : size_(size), passPrefix_(std::move(passPrefix)) {
  for (uint32_t specular : {0u, 1u}) {
    const uint32_t specialization[] = {specular};
    programs_[specular] = engine::ComputeProgram(
        ctx, specular ? "vsgl_attributes" : "vsgl_attributes (diffuse lobes)", kVsglAttributesSpv,
        std::vector<VkDescriptorType>(4 + VSGL_ATTR_COUNT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
        sizeof(gpu::VsglAttributesPush), specialization);
  }
  for (auto& p : pyramids_) p = createPyramid(ctx, size);
}

void VsglAttributes::clearLevels(VkCommandBuffer cmd, int first, int end) {
  const VkClearColorValue zero{};
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
  engine::computeToTransferBarrier(cmd);
  for (int a = first; a < end; ++a)
    vkCmdClearColorImage(cmd, pyramids_[a].handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
  engine::transferToComputeBarrier(cmd);
}

void VsglAttributes::record(VkCommandBuffer cmd, VplImages& vpls, engine::GBuffer& surface,
                            const RsmView& view, const MipPyramid& mips,
                            engine::GpuProfiler* profiler, bool specular, bool broadReflections) {
  if (vpls.width > size_ || vpls.height > size_)
    throw engine::Error("VSGL attributes: source " + std::to_string(vpls.width) + "x" +
                        std::to_string(vpls.height) + " exceeds the " + std::to_string(size_) +
                        "^2 pyramids");
  const glm::uvec2 extent(vpls.width, vpls.height);
  {
    engine::ProfileScope scope(profiler, cmd, passPrefix_ + "vsgl attributes");
    if (extent != glm::uvec2(size_) && extent != lastExtent_) {
      // Padding texels must hold zero power and zero PDF at every level. No pass writes them
      // (the attribute pass covers only the source, the mips only what it reduces to, the BRSM
      // compose writes their zeros back), so the clear is needed only when the source extent
      // changes: at 1920x1088 in 2048^2 it is six 85 MB clears per frame saved.
      clearLevels(cmd, 0, VSGL_ATTR_COUNT);
      specularZero_ = true;
    }
    if (!specular && !specularZero_) {
      // Without specular lobes the specular pyramids are zero at every level; nothing writes
      // them until a frame with specular lobes, so one clear serves every frame until then.
      clearLevels(cmd, VSGL_ATTR_SPECULAR_POWER, VSGL_ATTR_COUNT);
      specularZero_ = true;
    }
    if (specular) specularZero_ = false;
    lastExtent_ = extent;
    gpu::VsglAttributesPush push{glm::vec4(view.axis, 0.0f), extent, view.perspective ? 1u : 0u,
                                 broadReflections ? 1u : 0u};
    using engine::Binding;
    programs_[specular].dispatch(
        cmd,
        {Binding::storageImage(vpls.position), Binding::storageImage(vpls.diffuse),
         Binding::storageImage(vpls.specular), Binding::storageImage(surface.normal),
         Binding::storageImage(pyramids_[0], 0), Binding::storageImage(pyramids_[1], 0),
         Binding::storageImage(pyramids_[2], 0), Binding::storageImage(pyramids_[3], 0),
         Binding::storageImage(pyramids_[4], 0), Binding::storageImage(pyramids_[5], 0)},
        push, engine::groupCount(vpls.width, VSGL_ATTR_GROUP_X),
        engine::groupCount(vpls.height, VSGL_ATTR_GROUP_Y));
    engine::computeBarrier(cmd);
  }
  engine::ProfileScope scope(profiler, cmd, passPrefix_ + "attribute mipmapping");
  for (int a = 0; a < (specular ? VSGL_ATTR_COUNT : VSGL_ATTR_SPECULAR_POWER); ++a)
    mips.record(cmd, pyramids_[a], extent);
}

}  // namespace gi
