#include "passes/vsgl_attributes.h"

#include "engine/commands.h"
#include "shared/vsgl_attributes_pass.h"
#include "spirv/vsgl_attributes.h"

namespace gi {

VsglAttributes::VsglAttributes(engine::Context& ctx, uint32_t size)
    : size_(size),
      program_(ctx, "vsgl_attributes", kVsglAttributesSpv,
               std::vector<VkDescriptorType>(4 + VSGL_ATTR_COUNT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
               sizeof(gpu::VsglAttributesPush)) {
  for (auto& p : pyramids_) p = createPyramid(ctx, size);
}

void VsglAttributes::record(VkCommandBuffer cmd, ReflectiveShadowMap& rsm, const RsmView& view,
                            const MipPyramid& mips, engine::GpuProfiler* profiler) {
  {
    engine::ProfileScope scope(profiler, cmd, "vsgl attributes");
    gpu::VsglAttributesPush push{glm::vec4(view.axis, 0.0f), {size_, size_}, view.perspective ? 1u : 0u, 0};
    using engine::Binding;
    program_.dispatch(cmd,
                      {Binding::storageImage(rsm.position()), Binding::storageImage(rsm.diffuseFlux()),
                       Binding::storageImage(rsm.specularFlux()), Binding::storageImage(rsm.surface().normal),
                       Binding::storageImage(pyramids_[0], 0), Binding::storageImage(pyramids_[1], 0),
                       Binding::storageImage(pyramids_[2], 0), Binding::storageImage(pyramids_[3], 0),
                       Binding::storageImage(pyramids_[4], 0), Binding::storageImage(pyramids_[5], 0)},
                      push, engine::groupCount(size_, VSGL_ATTR_GROUP_X),
                      engine::groupCount(size_, VSGL_ATTR_GROUP_Y));
    engine::computeBarrier(cmd);
  }
  engine::ProfileScope scope(profiler, cmd, "attribute mipmapping");
  for (auto& p : pyramids_) mips.record(cmd, p);
}

}  // namespace gi
