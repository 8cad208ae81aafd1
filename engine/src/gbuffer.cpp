#include "engine/gbuffer.h"

#include "engine/commands.h"
#include "shared/gbuffer.h"
#include "spirv/gbuffer_resolve.h"

namespace engine {
namespace {

Image storageImage(Context& ctx, uint32_t width, uint32_t height, VkFormat format) {
  ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  return Image(ctx, desc);
}

}  // namespace

GBuffer createGBuffer(Context& ctx, uint32_t width, uint32_t height) {
  GBuffer g;
  g.width = width;
  g.height = height;
  g.depth = storageImage(ctx, width, height, VK_FORMAT_R32_SFLOAT);
  g.normal = storageImage(ctx, width, height, VK_FORMAT_R16G16_SNORM);
  g.diffuse = storageImage(ctx, width, height, VK_FORMAT_R16G16B16A16_SFLOAT);
  g.specular = storageImage(ctx, width, height, VK_FORMAT_R16G16B16A16_SFLOAT);
  g.emission = storageImage(ctx, width, height, VK_FORMAT_R16G16B16A16_SFLOAT);
  for (Image* image : {&g.depth, &g.normal, &g.diffuse, &g.specular, &g.emission})
    initialLayout(ctx, *image, VK_IMAGE_LAYOUT_GENERAL);
  return g;
}

GBufferResolve::GBufferResolve(Context& ctx)
    : program_(ctx, "gbuffer_resolve", kGbufferResolveSpv,
               {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
               sizeof(gpu::GBufferResolvePush)) {}

void GBufferResolve::record(VkCommandBuffer cmd, const SceneGpu& scene, const Buffer& visibility,
                            const View& view, GBuffer& g, GpuProfiler* profiler,
                            BackFaces backFaces) {
  ProfileScope scope(profiler, cmd, "gbuffer resolve");
  gpu::GBufferResolvePush push{
      view.invViewProj, {g.width, g.height}, static_cast<uint32_t>(backFaces), scene.materialCount};
  program_.dispatch(
      cmd,
      {Binding::storage(visibility), Binding::storage(scene.vertices),
       Binding::storage(scene.indices), Binding::storage(scene.triangleMaterials),
       Binding::storage(scene.materials),
       Binding::sampled(scene.baseColorTextures, scene.sampler.handle()),
       Binding::sampled(scene.dataTextures, scene.sampler.handle()), Binding::storageImage(g.depth),
       Binding::storageImage(g.normal), Binding::storageImage(g.diffuse),
       Binding::storageImage(g.specular), Binding::storageImage(g.emission)},
      push, groupCount(g.width, GBUFFER_GROUP_X), groupCount(g.height, GBUFFER_GROUP_Y));
  computeBarrier(cmd);
}

}  // namespace engine
