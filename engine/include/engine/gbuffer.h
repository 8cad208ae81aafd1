// The camera G-buffer (formats and encodings: shaders/shared/gbuffer.h) and the resolve pass
// that fills it from a visibility buffer.
#pragma once

#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/scene_gpu.h"
#include "engine/view.h"

namespace engine {

struct GBuffer {
  Image depth;     // R32_SFLOAT
  Image normal;    // R16G16_SNORM
  Image diffuse;   // R16G16B16A16_SFLOAT
  Image specular;  // R16G16B16A16_SFLOAT
  Image emission;  // R16G16B16A16_SFLOAT: emitted radiance (glTF emissive), added by the host
  uint32_t width = 0;
  uint32_t height = 0;
};

// Creates the images in GENERAL layout, ready for storage writes and reads.
GBuffer createGBuffer(Context& ctx, uint32_t width, uint32_t height);

// What a triangle seen from behind shows. A camera view shades it as its front (two-sided
// shading, as the host's direct light does). A light's view (the RSM) follows glTF's
// doubleSided: the back of a single-sided material is no surface, so it reflects nothing
// (diffuse and specular 0, roughness 1) while its depth still shadows. A room built of
// single-sided walls then bounces no light from the outside of its walls into itself
// (docs/techniques/vsgl-generation.md, "Back faces").
enum class BackFaces : uint32_t { AsFront = 0, PerMaterial = 1 };

class GBufferResolve {
 public:
  explicit GBufferResolve(Context& ctx);
  void record(VkCommandBuffer cmd, const SceneGpu& scene, const Buffer& visibility,
              const View& view, GBuffer& gbuffer, GpuProfiler* profiler = nullptr,
              BackFaces backFaces = BackFaces::AsFront);

 private:
  ComputeProgram program_;
};

}  // namespace engine
