#include "engine/direct_light.h"

#include <cmath>

#include "engine/commands.h"
#include "spirv/direct_light.h"

namespace engine {
namespace {

// A perspective cone wider than this (half angle) is rendered as a cube instead: the texel
// density of one view falls as 1/cos^2 towards its edges and collapses near 90 degrees.
constexpr float kMaxSpotViewHalfAngle = 1.2f;

gpu::ShadowView perspectiveView(const glm::vec3& eye, const glm::vec3& forward, float halfAngle,
                                const Bounds& bounds, uint32_t resolution) {
  DepthRange r = enclosingDepthRange(bounds, eye);
  glm::mat4 proj = perspectiveVulkan(2.0f * halfAngle, 1.0f, r.znear, r.zfar);
  glm::mat4 view = lookAlong(eye, forward, upVectorFor(forward));
  float texelPerMetre = 2.0f * std::tan(halfAngle) / static_cast<float>(resolution);
  return {proj * view, glm::vec4(texelPerMetre, 0.0f, 0.0f, 0.0f)};
}

void appendCube(LightSetup& setup, const glm::vec3& eye, const Bounds& bounds,
                uint32_t resolution) {
  const glm::vec3 faces[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // 90 degrees plus one texel so that PCF taps at a face edge stay inside the face.
  float halfAngle = std::atan(1.0f + 2.0f / static_cast<float>(resolution));
  for (const glm::vec3& f : faces)
    setup.views.push_back(perspectiveView(eye, f, halfAngle, bounds, resolution));
}

}  // namespace

LightSetup buildLightSetup(const Scene& scene, const DirectLightSettings& settings) {
  LightSetup setup;
  Bounds bounds = scene.bounds();
  const uint32_t res = settings.shadowResolution;
  for (const Light& light : scene.lights) {
    gpu::GpuLight g{};
    g.position = glm::vec4(light.position, 1.0f);
    g.direction = glm::vec4(glm::normalize(light.direction), 0.0f);
    g.radiance = glm::vec4(light.color * light.intensity, light.range);
    glm::vec2 falloff = spotFalloff(light);
    g.spot = glm::vec4(falloff, 0.0f, 0.0f);
    g.info = glm::uvec4(static_cast<uint32_t>(light.type),
                        static_cast<uint32_t>(setup.views.size()), 0u, 0u);
    if (settings.shadows) {
      size_t first = setup.views.size();
      if (light.type == LightType::Directional) {
        EnclosingOrtho o = enclosingOrthographic(bounds, glm::vec3(g.direction));
        setup.views.push_back(
            {o.proj * o.view,
             glm::vec4(0.0f, 2.0f * o.halfExtent / static_cast<float>(res), 0.0f, 0.0f)});
      } else if (light.type == LightType::Spot && light.outerConeAngle <= kMaxSpotViewHalfAngle) {
        // One texel of margin beyond the cone keeps PCF taps at the cone edge inside the map.
        float half = std::min(light.outerConeAngle + 2.0f / static_cast<float>(res),
                              kMaxSpotViewHalfAngle + 0.1f);
        setup.views.push_back(
            perspectiveView(light.position, glm::vec3(g.direction), half, bounds, res));
      } else {
        appendCube(setup, light.position, bounds, res);
      }
      g.info.z = static_cast<uint32_t>(setup.views.size() - first);
    }
    setup.lights.push_back(g);
  }
  return setup;
}

DirectLighting::DirectLighting(Context& ctx, const Scene& scene,
                               const DirectLightSettings& settings)
    : settings_(settings),
      setup_(buildLightSetup(scene, settings)),
      program_(ctx, "direct_light", kDirectLightSpv,
               {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
               sizeof(gpu::DirectLightPush)) {
  if (settings.shadowResolution < 16 || settings.shadowResolution > 4096)
    throw Error("shadow resolution " + std::to_string(settings.shadowResolution) +
                " outside [16, 4096]");
  // Full-size uniform buffers: the shader declares fixed-size arrays, so new lights fit them.
  lights_ = Buffer(ctx, DIRECT_MAX_LIGHTS * sizeof(gpu::GpuLight),
                   VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::GpuOnly);
  views_ = Buffer(ctx, DIRECT_MAX_SHADOW_VIEWS * sizeof(gpu::ShadowView),
                  VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::GpuOnly);
  upload(ctx, scene);
}

void DirectLighting::setLights(Context& ctx, const Scene& scene) {
  setup_ = buildLightSetup(scene, settings_);
  upload(ctx, scene);
}

void DirectLighting::upload(Context& ctx, const Scene& scene) {
  if (setup_.lights.size() > DIRECT_MAX_LIGHTS || setup_.views.size() > DIRECT_MAX_SHADOW_VIEWS)
    throw Error(scene.source + ": " + std::to_string(setup_.lights.size()) + " lights with " +
                std::to_string(setup_.views.size()) + " shadow views; direct lighting supports " +
                std::to_string(DIRECT_MAX_LIGHTS) + " lights and " +
                std::to_string(DIRECT_MAX_SHADOW_VIEWS) + " shadow views");
  if (!setup_.lights.empty())
    lights_.upload(ctx, setup_.lights.data(), setup_.lights.size() * sizeof(gpu::GpuLight));
  if (!setup_.views.empty())
    views_.upload(ctx, setup_.views.data(), setup_.views.size() * sizeof(gpu::ShadowView));
  const VkDeviceSize mapBytes =
      Rasterizer::visibilityBytes(settings_.shadowResolution, settings_.shadowResolution);
  const VkDeviceSize bytes = std::max<VkDeviceSize>(mapBytes * setup_.views.size(), 16);
  if (shadowMaps_.size() < bytes)
    shadowMaps_ = Buffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly);
}

gpu::ShadowView givenShadowView(const glm::mat4& viewProj, uint32_t resolution) {
  const glm::vec3 row0(viewProj[0][0], viewProj[1][0], viewProj[2][0]);
  const glm::vec3 rowW(viewProj[0][3], viewProj[1][3], viewProj[2][3]);
  const float texel = 2.0f / (glm::length(row0) * static_cast<float>(resolution));
  const bool perspective = glm::length(rowW) > 0.0f;
  return {viewProj,
          perspective ? glm::vec4(texel, 0.0f, 0.0f, 0.0f) : glm::vec4(0.0f, texel, 0.0f, 0.0f)};
}

void DirectLighting::record(VkCommandBuffer cmd, const SceneGpu& scene, Rasterizer& rasterizer,
                            const GBuffer& g, const View& view, Image& radiance,
                            GpuProfiler* profiler, std::span<const GivenShadowMap> given) {
  const uint32_t res = settings_.shadowResolution;
  VkDeviceSize mapBytes = Rasterizer::visibilityBytes(res, res);
  // Every view's record each frame: a given map's view replaces the setup's for this frame only.
  std::vector<gpu::ShadowView> views = setup_.views;
  std::vector<const GivenShadowMap*> givenFor(views.size(), nullptr);
  for (const GivenShadowMap& m : given) {
    if (m.view >= views.size())
      throw Error("direct light: given shadow map for view " + std::to_string(m.view) + " of " +
                  std::to_string(views.size()));
    givenFor[m.view] = &m;
    views[m.view] = givenShadowView(m.viewProj, res);
  }
  // The views' records change with the given maps, and return to the setup's after them.
  if ((!given.empty() || viewsGiven_) && !views.empty())
    updateBuffer(cmd, views_, views.data(), views.size() * sizeof(gpu::ShadowView));
  viewsGiven_ = !given.empty();
  for (size_t i = 0; i < views.size(); ++i) {
    ProfileScope scope(profiler, cmd, "shadow maps");
    if (givenFor[i]) {
      computeToTransferBarrier(cmd);
      const VkBufferCopy copy{givenFor[i]->offset, i * mapBytes, mapBytes};
      vkCmdCopyBuffer(cmd, givenFor[i]->buffer, shadowMaps_.handle(), 1, &copy);
      transferToComputeBarrier(cmd);
    } else {
      rasterizer.record(cmd, scene, views[i].viewProj, {&shadowMaps_, i * mapBytes, res, res});
    }
  }
  ProfileScope scope(profiler, cmd, "direct light");
  gpu::DirectLightPush push{
      view.invViewProj, {g.width, g.height}, static_cast<uint32_t>(setup_.lights.size()), res};
  program_.dispatch(
      cmd,
      {Binding::uniform(lights_), Binding::uniform(views_), Binding::storage(shadowMaps_),
       Binding::storageImage(g.depth), Binding::storageImage(g.normal),
       Binding::storageImage(g.diffuse), Binding::storageImage(g.specular),
       Binding::storageImage(radiance), Binding::storageImage(g.emission)},
      push, groupCount(g.width, DIRECT_GROUP_X), groupCount(g.height, DIRECT_GROUP_Y));
  computeBarrier(cmd);
}

}  // namespace engine
