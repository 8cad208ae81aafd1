// The reflective shadow map of one light: the G-buffer resolve rendered from the light (same
// rasterizer, same surface code as the camera) followed by rsm_flux.comp, which turns every
// texel into a virtual point light with a position relative to the light and its flux
// (formats: shaders/shared/rsm_flux.h).
#pragma once

#include <string>
#include <vector>

#include "common/rsm_view.h"
#include "engine/gbuffer.h"
#include "engine/rasterizer.h"

namespace gi {

// The flux pass's outputs (formats: shaders/shared/rsm_flux.h), width x height RGBA32F.
struct VplImages {
  engine::Image position;
  engine::Image diffuse;
  engine::Image specular;
  uint32_t width = 0;
  uint32_t height = 0;
};
VplImages createVplImages(engine::Context& ctx, uint32_t width, uint32_t height);

// rsm_flux.comp over any G-buffer (a light's or the camera's).
class FluxPass {
 public:
  // `passName`: the profiler's name for it (the camera's importance flux is timed apart).
  explicit FluxPass(engine::Context& ctx, std::string passName = "rsm flux");
  void record(VkCommandBuffer cmd, engine::GBuffer& surface, const RsmView& view,
              const FluxSource& source, VplImages& out,
              engine::GpuProfiler* profiler = nullptr) const;

 private:
  std::string passName_;
  engine::ComputeProgram program_;
  engine::Buffer albedoTable_;  // createGgxAlbedoTable: the specular flux's directional albedo
};

class ReflectiveShadowMap {
 public:
  ReflectiveShadowMap(engine::Context& ctx, uint32_t size);

  // `visibility` (size^2 uint64, engine::Rasterizer's format): where the light's view is
  // rasterized; null: the RSM's own buffer.
  void record(VkCommandBuffer cmd, const engine::SceneGpu& scene, engine::Rasterizer& rasterizer,
              engine::GBufferResolve& resolve, const RsmView& view, const engine::Light& light,
              engine::GpuProfiler* profiler = nullptr, const engine::Buffer* visibility = nullptr);

  uint32_t size() const { return size_; }
  engine::GBuffer& surface() { return surface_; }  // the light's G-buffer (normals live here)
  VplImages& vpls() { return vpls_; }
  engine::Image& position() { return vpls_.position; }
  engine::Image& diffuseFlux() { return vpls_.diffuse; }
  engine::Image& specularFlux() { return vpls_.specular; }

 private:
  uint32_t size_;
  FluxPass flux_;
  engine::Buffer visibility_;
  engine::GBuffer surface_;
  VplImages vpls_;
};

}  // namespace gi
