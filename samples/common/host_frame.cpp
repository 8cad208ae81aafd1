#include "host_frame.h"

#include "engine/commands.h"
#include "engine/environments.h"
#include "engine/gbuffer_reference.h"
#include "gi_host.h"

namespace samples {
namespace {

engine::Image makeRadiance(engine::Context& ctx, uint32_t width, uint32_t height) {
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  engine::Image image(ctx, desc);
  engine::initialLayout(ctx, image, VK_IMAGE_LAYOUT_GENERAL);
  return image;
}

engine::ImageRgba32f blackLike(const engine::ImageRgba32f& image) {
  engine::ImageRgba32f black{image.width, image.height,
                             std::vector<float>(image.pixels.size(), 0.0f)};
  for (size_t i = 3; i < black.pixels.size(); i += 4) black.pixels[i] = 1.0f;
  return black;
}

}  // namespace

HostFrame::HostFrame(engine::Context& ctx, const engine::Scene& scene, uint32_t width,
                     uint32_t height, const engine::DirectLightSettings& direct)
    : width_(width),
      height_(height),
      rasterizer_(ctx),
      resolve_(ctx),
      direct_(ctx, scene, direct),
      gbuffer_(engine::createGBuffer(ctx, width, height)),
      visibility_(ctx, engine::Rasterizer::visibilityBytes(width, height),
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly),
      radiance_(makeRadiance(ctx, width, height)) {}

void HostFrame::setLights(engine::Context& ctx, const engine::Scene& scene) {
  direct_.setLights(ctx, scene);
}

void HostFrame::record(VkCommandBuffer cmd, const engine::SceneGpu& scene, const engine::View& view,
                       engine::GpuProfiler* profiler) {
  recordGBuffer(cmd, scene, view, profiler);
  recordDirectLight(cmd, scene, view, profiler);
}

void HostFrame::recordGBuffer(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                              const engine::View& view, engine::GpuProfiler* profiler) {
  rasterizer_.record(cmd, scene, view.viewProj, {&visibility_, 0, width_, height_}, profiler);
  resolve_.record(cmd, scene, visibility_, view, gbuffer_, profiler);
}

void HostFrame::recordDirectLight(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                                  const engine::View& view, engine::GpuProfiler* profiler,
                                  std::span<const gi::LightViewOutput> lightViews) {
  const engine::LightSetup& setup = direct_.setup();
  std::vector<engine::GivenShadowMap> given;
  for (uint32_t light = 0; light < setup.lights.size(); ++light) {
    const uint32_t first = setup.lights[light].info.y, count = setup.lights[light].info.z;
    std::vector<const gi::LightViewOutput*> faces;
    for (const gi::LightViewOutput& v : lightViews)
      if (v.light == light) faces.push_back(&v);
    // Both order a cube's faces +x, -x, +y, -y, +z, -z; a spot the host renders as a cube
    // (wider than one view holds) keeps its own maps.
    if (count == 0 || faces.size() != count) continue;
    bool usable = true;
    for (const gi::LightViewOutput* f : faces)
      usable = usable && f->size == direct_.shadowResolution();
    if (!usable) continue;
    for (const gi::LightViewOutput* f : faces)
      given.push_back({first + f->face, f->visibility, f->offset, f->viewProj});
  }
  shadowedByModule_ = static_cast<uint32_t>(given.size());
  direct_.record(cmd, scene, rasterizer_, gbuffer_, view, radiance_, profiler, given);
}

FrameImages readFrame(engine::Context& ctx, HostFrame& host, const gi::FrameOutput* output,
                      const engine::View& view, const engine::ImageRgba32f* environment) {
  FrameImages f;
  f.direct = readRadiance(ctx, host.radiance());
  f.final = f.direct;
  if (output && output->vsglCount > 0) {  // light bounced (else environment light only)
    Indirect bounce = readIndirect(ctx, *output, host.width(), host.height());
    f.diffuse = std::move(bounce.diffuse);
    f.glossy = std::move(bounce.glossy);
    f.bounced = true;
    addInto(f.final, f.diffuse);
    addInto(f.final, f.glossy);
  } else {
    f.diffuse = blackLike(f.direct);
    f.glossy = f.diffuse;
  }
  if (output && output->environmentDiffuse.image) {
    Indirect light = readEnvironment(ctx, *output, host.width(), host.height());
    addInto(light.diffuse, light.glossy);
    f.environmentLight = std::move(light.diffuse);
    f.environmentLit = true;
    addInto(f.final, f.environmentLight);
  }
  if (environment) {  // the background: the environment itself where no surface is seen
    const engine::GBufferData g = engine::readbackGBuffer(ctx, host.gbuffer());
    for (uint32_t y = 0; y < host.height(); ++y)
      for (uint32_t x = 0; x < host.width(); ++x) {
        if (!g.at(x, y).background()) continue;
        const glm::vec3 dir(engine::cameraRayReference(view, glm::dvec2(x, y) + 0.5).dir);
        const glm::vec3 sky = engine::environmentRadiance(*environment, dir);
        float* p = &f.final.pixels[(size_t{y} * host.width() + x) * 4];
        for (int c = 0; c < 3; ++c) p[c] += sky[c];
      }
  }
  return f;
}

}  // namespace samples
