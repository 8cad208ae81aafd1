// How the sample programs, as hosts, talk to the module's public API: its engine resources
// become the API's plain handles and the module's outputs come back as images.
// Nothing here reaches behind gi/include.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "engine/gbuffer.h"
#include "engine/image_io.h"
#include "engine/scene_gpu.h"
#include "engine/tonemap.h"
#include "engine/view.h"
#include "gi/indirect_lighting.h"
#include "shared/vsgl.h"
#include "shared/vsgl_allocation.h"

namespace samples {

// Throws engine::Error with the status's message when it failed.
void check(const gi::Status& status);

// The indices of the lights that bounce: every light of `scene`, as the sample programs give the
// module all of them. Throws engine::Error naming the scene when it has no light (and the --light
// choices that add one) or more than gi::kMaxLights, so that no comparison runs unlike with like.
std::vector<uint32_t> bouncingLights(const engine::Scene& scene);
// The index of `scene`'s first spot or directional light (a light with one RSM view and a
// direction), or -1 when it has none.
int firstDirectedLight(const engine::Scene& scene);

// An upper bound of any surface's reflectance in `scene` (SceneGeometry::maxReflectance): the
// largest channel of a diffuse albedo, F0 or F90, textures included.
float maxReflectance(const engine::Scene& scene);
// `gpuScene`'s buffers and images as the API's plain handles, with `scene`'s bounds and
// reflectance bound.
// An upper bound of any surface's specular reflectance (SceneGeometry::maxSpecular): F0 =
// mix(min(0.04 c, 1) s, base, metallic) and F90 = mix(s, 1, metallic) with KHR_materials_specular's
// strength s and colour c, bounded with the largest metallic of each material's texture. 0 only
// when every material is a dielectric (metallic 0 everywhere) of strength 0.
float maxSpecular(const engine::Scene& scene);

// Whether any surface of `scene` can block light between two others
// (SceneGeometry::canOcclude): false when every vertex lies on or in front of every triangle's
// plane, within 1e-5 of the scene's size (the inside of a convex room). Scenes of more than
// kOccluderTestTriangles triangles are not tested (the test costs triangles x vertices) and
// count as occluding.
constexpr uint32_t kOccluderTestTriangles = 8192;
bool canOcclude(const engine::Scene& scene);

gi::SceneGeometry sceneGeometry(const engine::SceneGpu& gpuScene, const engine::Scene& scene);

// The module on `ctx`'s device for a width x height G-buffer, with `scene`'s geometry set.
std::unique_ptr<gi::IndirectLighting> createIndirect(engine::Context& ctx,
                                                     const gi::Settings& settings, uint32_t width,
                                                     uint32_t height,
                                                     const engine::SceneGpu& gpuScene,
                                                     const engine::Scene& scene);

// The host's G-buffer of `view` (the compute rasterizer and resolve), in GENERAL layout.
engine::GBuffer renderGBuffer(engine::Context& ctx, const engine::SceneGpu& gpuScene,
                              const engine::View& view);

// A scene light as the API takes it.
gi::Light apiLight(const engine::Light& light);
// The G-buffer images (GENERAL layout), camera and lights of one frame (FrameInput::lights).
gi::FrameInput frameInput(const engine::GBuffer& gbuffer, const engine::View& view,
                          std::span<const engine::Light> lights);
// ... with one light.
gi::FrameInput frameInput(const engine::GBuffer& gbuffer, const engine::View& view,
                          const engine::Light& light);

engine::ImageRgba32f readRadiance(engine::Context& ctx, engine::Image& image);
struct Indirect {
  engine::ImageRgba32f diffuse, glossy;
};
// Both outputs have the G-buffer's size.
Indirect readIndirect(engine::Context& ctx, const gi::FrameOutput& output, uint32_t width,
                      uint32_t height);
// The environment light's two outputs (FrameOutput::environmentDiffuse and environmentGlossy).
Indirect readEnvironment(engine::Context& ctx, const gi::FrameOutput& output, uint32_t width,
                         uint32_t height);
// Diffuse + glossy per pixel, in double (what the benchmark and the flicker captures score).
std::vector<glm::dvec3> indirectSum(const Indirect& indirect);
std::vector<gpu::Vsgl> readVsgls(engine::Context& ctx, const gi::FrameOutput& output);
// FrameOutput::vsglViews: (first record, count) of each RSM view.
std::vector<glm::uvec2> readVsglViews(engine::Context& ctx, const gi::FrameOutput& output);
// A single-channel R32_SFLOAT output of the module (FrameOutput::debugVisibility or
// shadingLevels), read back; `what` names it in the error when the module wrote none.
std::vector<float> readR32f(engine::Context& ctx, const gi::ImageRef& ref, uint32_t width,
                            uint32_t height, const char* what);

void addInto(engine::ImageRgba32f& sum, const engine::ImageRgba32f& term);

}  // namespace samples
