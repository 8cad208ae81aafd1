#include "passes/rsm.h"

#include <cmath>
#include <numbers>

#include "engine/commands.h"
#include "passes/ggx_albedo_table.h"
#include "shared/rsm_flux.h"
#include "spirv/rsm_flux.h"

namespace gi {

using engine::Error;

namespace {

engine::Image fluxImage(engine::Context& ctx, uint32_t width, uint32_t height) {
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  return engine::Image(ctx, desc);
}

}  // namespace

VplImages createVplImages(engine::Context& ctx, uint32_t width, uint32_t height) {
  VplImages v{fluxImage(ctx, width, height), fluxImage(ctx, width, height),
              fluxImage(ctx, width, height), width, height};
  for (engine::Image* image : {&v.position, &v.diffuse, &v.specular})
    engine::initialLayout(ctx, *image, VK_IMAGE_LAYOUT_GENERAL);
  return v;
}

FluxPass::FluxPass(engine::Context& ctx, std::string passName)
    : passName_(std::move(passName)),
      program_(ctx, "rsm_flux", kRsmFluxSpv,
               {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
               sizeof(gpu::RsmFluxPush)),
      albedoTable_(createGgxAlbedoTable(ctx)) {}

void FluxPass::record(VkCommandBuffer cmd, engine::GBuffer& surface, const RsmView& view,
                      const FluxSource& source, VplImages& out,
                      engine::GpuProfiler* profiler) const {
  engine::ProfileScope scope(profiler, cmd, passName_);
  gpu::RsmFluxPush push{};
  push.invViewProjRelative = view.invViewProjRelative;
  push.axis = glm::vec4(view.axis, 0.0f);
  push.radiance = glm::vec4(source.radiance, 0.0f);
  push.spot = glm::vec4(source.falloff, view.texelArea, source.range);
  push.size = glm::uvec2(out.width, out.height);
  push.perspective = view.perspective ? 1u : 0u;
  using engine::Binding;
  program_.dispatch(cmd,
                    {Binding::storageImage(surface.depth), Binding::storageImage(surface.diffuse),
                     Binding::storageImage(surface.specular), Binding::storageImage(out.position),
                     Binding::storageImage(out.diffuse), Binding::storageImage(out.specular),
                     Binding::storageImage(surface.normal), Binding::storage(albedoTable_)},
                    push, engine::groupCount(out.width, RSM_GROUP_X),
                    engine::groupCount(out.height, RSM_GROUP_Y));
  engine::computeBarrier(cmd);
}

ReflectiveShadowMap::ReflectiveShadowMap(engine::Context& ctx, uint32_t size)
    : size_(size),
      flux_(ctx),
      visibility_(ctx, engine::Rasterizer::visibilityBytes(size, size),
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly),
      surface_(engine::createGBuffer(ctx, size, size)),
      vpls_(createVplImages(ctx, size, size)) {}

void ReflectiveShadowMap::record(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                                 engine::Rasterizer& rasterizer, engine::GBufferResolve& resolve,
                                 const RsmView& view, const engine::Light& light,
                                 engine::GpuProfiler* profiler, const engine::Buffer* visibility) {
  const engine::Buffer& target = visibility ? *visibility : visibility_;
  {
    engine::ProfileScope scope(profiler, cmd, "rsm raster");
    rasterizer.record(cmd, scene, view.raster, {&target, 0, size_, size_});
    resolve.record(cmd, scene, target, view.view, surface_, nullptr,
                   engine::BackFaces::PerMaterial);
  }
  flux_.record(cmd, surface_, view, lightFluxSource(light), vpls_, profiler);
}

}  // namespace gi
