// The light's side of a frame for GPU tests of the VSGL passes: a built-in scene's RSM and its
// six attribute pyramids, recorded and submitted (blocking).
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "engine/builtin_scenes.h"
#include "engine/rasterizer.h"
#include "gi_host.h"
#include "passes/mip_pyramid.h"
#include "passes/rsm.h"
#include "passes/vsgl_attributes.h"

namespace testing_gpu {

struct RsmRig {
  // The first spot or directional light of built-in scene `name` (one RSM view; the lounge's
  // point light comes first), an RSM of size^2 texels and its attribute pyramids.
  RsmRig(engine::Context& ctx, const std::string& name, uint32_t size)
      : RsmRig(ctx, engine::makeBuiltinScene(name), size) {}
  // The same for any scene with a spot or directional light.
  RsmRig(engine::Context& ctx, engine::Scene sceneIn, uint32_t size)
      : scene(std::move(sceneIn)),
        light(scene.lights.at(size_t(samples::firstDirectedLight(scene)))),
        view(gi::makeRsmView(scene, light, size)),
        gpuScene(std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx, scene))),
        rasterizer(std::make_unique<engine::Rasterizer>(ctx)),
        resolve(std::make_unique<engine::GBufferResolve>(ctx)),
        rsm(std::make_unique<gi::ReflectiveShadowMap>(ctx, size)),
        mips(std::make_unique<gi::MipPyramid>(ctx)),
        attributes(std::make_unique<gi::VsglAttributes>(ctx, size)) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      rsm->record(cmd, *gpuScene, *rasterizer, *resolve, view, light);
    });
  }

  // Level 0 of the attribute pyramids from the RSM, and their mips.
  void buildAttributes(engine::Context& ctx, bool broadReflections = false) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      attributes->record(cmd, rsm->vpls(), rsm->surface(), view, *mips, nullptr, true,
                         broadReflections);
    });
  }

  engine::Scene scene;
  engine::Light light;
  gi::RsmView view;
  std::unique_ptr<engine::SceneGpu> gpuScene;
  std::unique_ptr<engine::Rasterizer> rasterizer;
  std::unique_ptr<engine::GBufferResolve> resolve;
  std::unique_ptr<gi::ReflectiveShadowMap> rsm;
  std::unique_ptr<gi::MipPyramid> mips;
  std::unique_ptr<gi::VsglAttributes> attributes;
};

}  // namespace testing_gpu
