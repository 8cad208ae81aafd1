// How the sample renderer, as a host, talks to the module's public API: its engine resources
// become the API's plain handles, the module's outputs come back as images, and the pass times
// of both are tabulated. Nothing here reaches behind gi/include.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/gbuffer.h"
#include "engine/image_io.h"
#include "engine/scene_gpu.h"
#include "engine/tonemap.h"
#include "engine/view.h"
#include "gi/indirect_lighting.h"
#include "options.h"
#include "shared/vsgl.h"

namespace render {

// Throws engine::Error with the status's message when it failed.
void check(const gi::Status& status);

// The light the module bounces: the scene's first spot or directional light (the RSM does not
// support point lights yet), or null.
const engine::Light* bouncingLight(const engine::Scene& scene);

std::unique_ptr<gi::IndirectLighting> createIndirect(engine::Context& ctx, const Options& o,
                                                     const engine::SceneGpu& gpuScene,
                                                     const engine::Scene& scene);

// The G-buffer images (GENERAL layout), camera and light of one frame.
gi::FrameInput frameInput(const engine::GBuffer& gbuffer, const engine::View& view,
                          const engine::Light& light);

engine::ImageRgba32f readRadiance(engine::Context& ctx, engine::Image& image);
struct Indirect {
  engine::ImageRgba32f diffuse, glossy;
};
// Both outputs have the G-buffer's size.
Indirect readIndirect(engine::Context& ctx, const gi::FrameOutput& output, uint32_t width,
                      uint32_t height);
std::vector<gpu::Vsgl> readVsgls(engine::Context& ctx, const gi::FrameOutput& output);
std::vector<float> readVisibility(engine::Context& ctx, const gi::FrameOutput& output,
                                  uint32_t width, uint32_t height);

void addInto(engine::ImageRgba32f& sum, const engine::ImageRgba32f& term);

// Per-pass GPU times over the measured frames, printed as medians.
class PassTable {
 public:
  // One frame's time of a pass and the compute dispatches it recorded.
  void add(const std::string& name, double ms, uint32_t dispatches);
  // With the VSGL count and pixel count, the shading pass is also given per pixel-VSGL pair.
  void print(uint32_t frames, uint32_t vsglCount, uint32_t pixels) const;

 private:
  std::vector<std::string> order_;
  std::map<std::string, std::vector<double>> times_;
  std::map<std::string, uint32_t> dispatches_;  // the last frame's
};

}  // namespace render
