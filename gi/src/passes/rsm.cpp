#include "passes/rsm.h"

#include <cmath>

#include "engine/commands.h"
#include "shared/rsm_flux.h"
#include "spirv/rsm_flux.h"

namespace gi {

using engine::Error;

double frustumSolidAngle(double halfAngle) {
  double s = std::sin(halfAngle);
  return 4.0 * std::asin(s * s);
}

RsmView makeRsmView(const engine::Scene& scene, const engine::Light& light, uint32_t size) {
  RsmView r;
  r.axis = glm::normalize(light.direction);
  engine::Bounds bounds = scene.bounds();
  const float texels = static_cast<float>(size);
  if (light.type == engine::LightType::Spot) {
    if (light.outerConeAngle > kMaxRsmHalfAngle)
      throw Error("light '" + light.name + "': spot cone " + std::to_string(light.outerConeAngle) +
                  " rad is wider than the RSM supports (" + std::to_string(kMaxRsmHalfAngle) + " rad)");
    r.perspective = true;
    r.origin = light.position;
    r.tanHalfAngle = std::tan(light.outerConeAngle);
    float texelSide = 2.0f * r.tanHalfAngle / texels;
    r.texelArea = texelSide * texelSide;
    engine::DepthRange range = engine::enclosingDepthRange(bounds, light.position);
    glm::mat4 proj = engine::perspectiveVulkan(2.0f * light.outerConeAngle, 1.0f, range.znear, range.zfar);
    glm::mat4 rotation = engine::lookAlong(glm::vec3(0.0f), r.axis, engine::upVectorFor(r.axis));
    glm::mat4 view = engine::lookAlong(light.position, r.axis, engine::upVectorFor(r.axis));
    r.view = engine::makeView(view, proj, size, size);
    r.invViewProjRelative = glm::inverse(proj * rotation);
  } else if (light.type == engine::LightType::Directional) {
    engine::EnclosingOrtho o = engine::enclosingOrthographic(bounds, r.axis);
    r.perspective = false;
    r.origin = o.eye;
    float texelSide = 2.0f * o.halfExtent / texels;
    r.texelArea = texelSide * texelSide;
    glm::mat4 rotation = o.view;
    rotation[3] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    r.view = engine::makeView(o.view, o.proj, size, size);
    r.invViewProjRelative = glm::inverse(o.proj * rotation);
  } else {
    throw Error("light '" + light.name + "': point lights are not supported by the RSM yet");
  }
  return r;
}

namespace {

engine::Image fluxImage(engine::Context& ctx, uint32_t size) {
  engine::ImageDesc desc;
  desc.width = desc.height = size;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  return engine::Image(ctx, desc);
}

}  // namespace

ReflectiveShadowMap::ReflectiveShadowMap(engine::Context& ctx, uint32_t size)
    : size_(size),
      flux_(ctx, "rsm_flux", kRsmFluxSpv,
            {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
             VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
             VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
            sizeof(gpu::RsmFluxPush)),
      visibility_(ctx, engine::Rasterizer::visibilityBytes(size, size),
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly),
      surface_(engine::createGBuffer(ctx, size, size)),
      position_(fluxImage(ctx, size)),
      diffuse_(fluxImage(ctx, size)),
      specular_(fluxImage(ctx, size)) {
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    for (engine::Image* image : {&position_, &diffuse_, &specular_})
      engine::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_GENERAL);
  });
}

void ReflectiveShadowMap::record(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                                 engine::Rasterizer& rasterizer, engine::GBufferResolve& resolve,
                                 const RsmView& view, const engine::Light& light,
                                 engine::GpuProfiler* profiler) {
  {
    engine::ProfileScope scope(profiler, cmd, "rsm raster");
    rasterizer.record(cmd, scene, view.view.viewProj, {&visibility_, 0, size_, size_});
    resolve.record(cmd, scene, visibility_, view.view, surface_);
  }
  engine::ProfileScope scope(profiler, cmd, "rsm flux");
  gpu::RsmFluxPush push{};
  push.invViewProjRelative = view.invViewProjRelative;
  push.axis = glm::vec4(view.axis, 0.0f);
  push.radiance = glm::vec4(light.color * light.intensity, 0.0f);
  push.spot = glm::vec4(engine::spotFalloff(light), view.texelArea, 0.0f);
  push.size = glm::uvec2(size_);
  push.perspective = view.perspective ? 1u : 0u;
  flux_.dispatch(cmd,
                 {engine::Binding::storageImage(surface_.depth),
                  engine::Binding::storageImage(surface_.diffuse),
                  engine::Binding::storageImage(surface_.specular),
                  engine::Binding::storageImage(position_), engine::Binding::storageImage(diffuse_),
                  engine::Binding::storageImage(specular_)},
                 push, engine::groupCount(size_, RSM_GROUP_X), engine::groupCount(size_, RSM_GROUP_Y));
  engine::computeBarrier(cmd);
}

}  // namespace gi
