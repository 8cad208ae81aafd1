// vsgl_render: renders a glTF or built-in scene with the compute rasterizer and direct light,
// writes a linear EXR and a tone-mapped PNG, and prints per-pass GPU times (median of the
// measured frames, after a warm-up frame that pays for pipeline compilation).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>

#include "engine/builtin_scenes.h"
#include "engine/commands.h"
#include "engine/direct_light.h"
#include "engine/gbuffer.h"
#include "engine/gltf.h"
#include "engine/image_io.h"
#include "engine/rasterizer.h"
#include "engine/tonemap.h"
#include "engine/view.h"
#include "options.h"
#include "program_exit.h"

namespace {

using engine::Error;

bool isBuiltin(const std::string& name) {
  auto names = engine::builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

engine::Scene loadScene(const std::string& name) {
  if (isBuiltin(name)) return engine::makeBuiltinScene(name);
  std::filesystem::path path(name);
  if (path.extension() != ".gltf" && path.extension() != ".glb")
    throw Error("--scene: '" + name +
                "' is neither a built-in scene (cornell, atrium, checker) nor a .gltf/.glb file");
  return engine::loadGltf(name);
}

int listDevices() {
  for (const auto& d : engine::Context::listDevices())
    std::printf("%u: %s (%s, Vulkan %s)%s%s\n", d.index, d.name.c_str(), d.driver.c_str(),
                d.apiVersion.c_str(),
                d.unsuitableReason.empty() ? "" : " - unusable: ", d.unsuitableReason.c_str());
  return 0;
}

int run(const render::Options& o) {
  if (o.help) {
    std::printf("%s", render::usage());
    return 0;
  }
  if (o.listDevices) return listDevices();

  auto wallStart = std::chrono::steady_clock::now();
  engine::Scene scene = loadScene(o.scene);
  std::string stem = std::filesystem::path(o.scene).stem().string();
  if (!o.exportGltf.empty()) engine::writeGltf(scene, o.exportGltf);
  engine::Camera camera =
      scene.cameras.empty() ? engine::defaultCamera(scene) : scene.cameras.front();
  engine::View view = engine::cameraView(camera, o.width, o.height);

  std::error_code ec;
  std::filesystem::create_directories(o.outDir, ec);
  if (ec) throw Error(o.outDir + ": cannot create output directory: " + ec.message());

  engine::Context ctx({o.validation, o.device});
  std::printf("device: %s (%s)\nscene: %s, %u triangles, %zu lights, %ux%u, shadow maps %u^2%s\n",
              ctx.info().name.c_str(), ctx.info().driver.c_str(), scene.source.c_str(),
              scene.triangleCount(), scene.lights.size(), o.width, o.height,
              render::shadowResolutionFor(o), o.shadows ? "" : " (off)");

  engine::SceneGpu gpuScene = engine::uploadScene(ctx, scene);
  engine::Rasterizer rasterizer(ctx);
  engine::GBufferResolve resolve(ctx);
  engine::DirectLighting direct(ctx, scene, {render::shadowResolutionFor(o), o.shadows});
  engine::GBuffer gbuffer = engine::createGBuffer(ctx, o.width, o.height);
  engine::Buffer visibility(ctx, engine::Rasterizer::visibilityBytes(o.width, o.height),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  engine::ImageDesc radianceDesc;
  radianceDesc.width = o.width;
  radianceDesc.height = o.height;
  radianceDesc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  engine::Image radiance(ctx, radianceDesc);
  ctx.submitAndWait(
      [&](VkCommandBuffer cmd) { engine::imageBarrier(cmd, radiance, VK_IMAGE_LAYOUT_GENERAL); });

  engine::GpuProfiler profiler(ctx);
  std::map<std::string, std::vector<double>> passTimes;
  std::vector<std::string> passOrder;
  std::vector<double> frameTimes;
  for (uint32_t frame = 0; frame <= o.frames; ++frame) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      profiler.beginFrame(cmd);
      engine::ProfileScope total(&profiler, cmd, "frame");
      rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, o.width, o.height},
                        &profiler);
      resolve.record(cmd, gpuScene, visibility, view, gbuffer, &profiler);
      direct.record(cmd, gpuScene, rasterizer, gbuffer, view, radiance, &profiler);
    });
    if (frame == 0) continue;  // warm-up: pipelines compile at their first dispatch
    for (const auto& pass : profiler.results()) {
      if (pass.name == "frame") {
        frameTimes.push_back(pass.ms);
        continue;
      }
      if (!passTimes.count(pass.name)) passOrder.push_back(pass.name);
      passTimes[pass.name].push_back(pass.ms);
    }
  }

  std::printf("GPU time per pass, median of %u frames (ms):\n", o.frames);
  for (const auto& name : passOrder)
    std::printf("  %-18s %9.3f\n", name.c_str(), engine::median(passTimes[name]));
  std::printf("  %-18s %9.3f\n", "frame total", engine::median(frameTimes));

  std::vector<glm::vec4> texels = radiance.readbackRgba32f(ctx);
  engine::ImageRgba32f image;
  image.width = static_cast<int>(o.width);
  image.height = static_cast<int>(o.height);
  image.pixels.assign(&texels.data()->x, &texels.data()->x + 4 * texels.size());
  std::string base = (std::filesystem::path(o.outDir) / stem).string();
  // Built-in scenes exist only as code; a .gltf copy lets other tools open the same scene.
  if (isBuiltin(o.scene)) engine::writeGltf(scene, base + ".gltf");
  engine::writeExr(base + ".exr", image);
  engine::ToneMapSettings toneMap{o.exposureEv};
  engine::writePng(base + ".png", image.width, image.height, engine::toneMap(image, toneMap));
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  std::printf(
      "wrote %s.exr (linear) and %s.png (exposure x%.3g, ACES filmic, sRGB) in %.2f s wall\n",
      base.c_str(), base.c_str(), engine::exposureScale(image, toneMap), wall);
  return samples::validationExitStatus(ctx, "vsgl_render");
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_render", [&] { return run(render::parseOptions(argc, argv)); });
}
