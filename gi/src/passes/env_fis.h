// Environment shading by filtered importance sampling: the environment's diffuse and glossy
// radiance toward the camera at every G-buffer pixel (shaders/gi/env_fis.comp, layout in
// shaders/shared/env_fis.h; CPU twin gi/src/reference/env_fis_reference.h).
#pragma once

#include <array>
#include <optional>

#include "engine/gbuffer.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "engine/view.h"
#include "passes/vsgl_shade.h"
#include "shared/env_fis.h"

namespace gi {

class EnvFisShade {
 public:
  explicit EnvFisShade(engine::Context& ctx);

  enum class Mode : uint32_t {
    Filtered = ENV_FIS_FILTERED,      // each sample at the FIS level
    Unfiltered = ENV_FIS_UNFILTERED,  // level 0
    Randomised = ENV_FIS_RANDOMISED,  // level 0, Hammersley set rotated per pixel
  };
  enum class Brdf : uint32_t {
    Ggx = ENV_FIS_GGX,      // the G-buffer's GGX (common/brdf.glsl)
    Phong = ENV_FIS_PHONG,  // normalised Phong, exponent 2 / alpha^2 - 2, reflectance F0
    Ward = ENV_FIS_WARD,    // Ward, alpha_x = alpha, alpha_y = alpha * wardAnisotropy, F0
  };

  struct Inputs {
    // The converted environment (shared/environment.h): RGBA32F, 2 layers of mapSize^2, full
    // mips, in a layout a sampled read accepts (SHADER_READ_ONLY_OPTIMAL or GENERAL).
    const engine::Image* map = nullptr;
    VkSampler sampler = VK_NULL_HANDLE;  // trilinear, CLAMP_TO_EDGE
    uint32_t mapSize = 0;                // S, texels per side of level 0
    uint32_t levels = 0;                 // the map's mip levels (log2 S + 1)
    const engine::Buffer* sh = nullptr;  // gpu::EnvSh
    uint32_t sampleCount = 40;           // N [1, 4096]; more = less aliasing and noise, slower
    Mode mode = Mode::Filtered;
    Brdf brdf = Brdf::Ggx;
    float wardAnisotropy = 1.0f;  // Brdf::Ward: alpha_y / alpha_x, (0, inf); 1 = isotropic
    float kernelExtent = 4.0f;    // K of the level rule [texels], [1, 16]; larger = blurrier
  };

  // `camera`: the G-buffer camera's view (view directions are rebuilt from it). `out` receives
  // the diffuse (albedo applied) and glossy radiance; sky pixels (depth 1) get 0. The first
  // record of a (mode, brdf) pair compiles that variant.
  void record(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
              const Inputs& in, IndirectImages& out, engine::GpuProfiler* profiler = nullptr);

 private:
  engine::Context* ctx_;
  std::array<std::optional<engine::ComputeProgram>, ENV_FIS_MODES * ENV_FIS_BRDFS> programs_;
};

}  // namespace gi
