// The sample host's own frame, shared by vsgl_render and vsgl_viewer so that both show the same
// picture: the compute rasterizer's G-buffer, the direct light with its shadow maps, and the
// final image put together from it and the module's outputs (direct + indirect diffuse + glossy
// + environment light, the environment itself where no surface is seen).
#pragma once

#include <cstdint>
#include <span>

#include "engine/direct_light.h"
#include "engine/gbuffer.h"
#include "engine/image_io.h"
#include "engine/profiler.h"
#include "engine/rasterizer.h"
#include "engine/scene_gpu.h"
#include "engine/view.h"
#include "gi/indirect_lighting.h"

namespace samples {

class HostFrame {
 public:
  HostFrame(engine::Context& ctx, const engine::Scene& scene, uint32_t width, uint32_t height,
            const engine::DirectLightSettings& direct);

  // The scene's lights moved or changed (DirectLighting::setLights).
  void setLights(engine::Context& ctx, const engine::Scene& scene);
  // The G-buffer of `view` (width x height) and its direct light into radiance().
  void record(VkCommandBuffer cmd, const engine::SceneGpu& scene, const engine::View& view,
              engine::GpuProfiler* profiler);
  // The same in two halves, for a host that records the module in between and shadows with its
  // light views (gi::FrameOutput::lightViews, FrameInput::lights being the scene's first
  // lights in order): a light whose views the module rasterized at the shadow resolution, as
  // many as the host's own, takes them instead of rasterizing its own (shadowedByModule()).
  void recordGBuffer(VkCommandBuffer cmd, const engine::SceneGpu& scene, const engine::View& view,
                     engine::GpuProfiler* profiler);
  void recordDirectLight(VkCommandBuffer cmd, const engine::SceneGpu& scene,
                         const engine::View& view, engine::GpuProfiler* profiler,
                         std::span<const gi::LightViewOutput> lightViews = {});
  // The views the last recordDirectLight took from the module.
  uint32_t shadowedByModule() const { return shadowedByModule_; }

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  engine::GBuffer& gbuffer() { return gbuffer_; }
  engine::Image& radiance() { return radiance_; }

 private:
  uint32_t width_, height_;
  engine::Rasterizer rasterizer_;
  engine::GBufferResolve resolve_;
  engine::DirectLighting direct_;
  engine::GBuffer gbuffer_;
  engine::Buffer visibility_;
  engine::Image radiance_;
  uint32_t shadowedByModule_ = 0;
};

// A frame read back: each term the final image is the sum of.
struct FrameImages {
  engine::ImageRgba32f final;            // the sum below, plus the environment as the background
  engine::ImageRgba32f direct;           // the host's direct light (and emission)
  engine::ImageRgba32f diffuse, glossy;  // the bounce (VSGLs); zero when nothing bounced
  bool bounced = false;                  // the module wrote the bounce (FrameOutput::vsglCount > 0)
  // The environment's light alone (its diffuse + glossy outputs), when the module wrote it.
  bool environmentLit = false;
  engine::ImageRgba32f environmentLight;
};

// Reads `host`'s direct light and, when `output` is given, the module's outputs for `view`;
// `environment` (or null) is seen where the G-buffer has no surface.
FrameImages readFrame(engine::Context& ctx, HostFrame& host, const gi::FrameOutput* output,
                      const engine::View& view, const engine::ImageRgba32f* environment);

}  // namespace samples
