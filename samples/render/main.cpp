// vsgl_render: renders a glTF or built-in scene with the compute rasterizer, direct light and
// one-bounce VSGL indirect light, writes linear EXRs, tone-mapped PNGs and debug pictures, and
// prints per-pass GPU times (median of the measured frames, after warm-up frames: the first
// frame pays for pipeline compilation). It is a host renderer like any other: the engine library
// renders its G-buffer and direct light, and the indirect light comes only through the public API
// of gi/include (docs/integration.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>

#include "debug_views.h"
#include "engine/commands.h"
#include "engine/direct_light.h"
#include "engine/environments.h"
#include "engine/gbuffer.h"
#include "engine/gbuffer_reference.h"
#include "engine/gltf.h"
#include "engine/image_io.h"
#include "engine/machine_peak.h"
#include "engine/rasterizer.h"
#include "engine/tonemap.h"
#include "engine/view.h"
#include "gi/indirect_lighting.h"
#include "gi_host.h"
#include "host_frame.h"
#include "options.h"
#include "pass_table.h"
#include "program_exit.h"
#include "scene_files.h"

namespace {

using engine::Error;

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
  engine::Scene scene = samples::loadScene(o.scene);
  samples::selectCamera(scene, o.camera);
  const std::string lightNote = samples::applyLightChoice(scene, o.light, !o.environment.empty(),
                                                          float(o.width) / float(o.height));
  std::string stem = std::filesystem::path(o.scene).stem().string();
  std::replace(stem.begin(), stem.end(), ':', '-');  // generated scenes: sphere-room:N
  if (!o.exportGltf.empty()) engine::writeGltf(scene, o.exportGltf);
  engine::View view = samples::sceneView(scene, o.width, o.height);
  if (o.motion == samples::Motion::Sweep) samples::sweptLight(scene);  // fails before any work
  samples::createOutputDirectory(o.outDir);

  engine::Context ctx({o.validation, o.device});
  std::printf("device: %s (%s)\nscene: %s, %u triangles, %zu lights, %ux%u, shadow maps %u^2%s\n",
              ctx.info().name.c_str(), ctx.info().driver.c_str(), scene.source.c_str(),
              scene.triangleCount(), scene.lights.size(), o.width, o.height,
              render::shadowResolutionFor(o), o.shadows ? "" : " (off)");
  if (!lightNote.empty()) std::printf("%s\n", lightNote.c_str());

  auto gpuScene = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx, scene));
  samples::HostFrame host(ctx, scene, o.width, o.height,
                          {render::shadowResolutionFor(o), o.shadows});

  std::optional<engine::ImageRgba32f> environment;
  if (!o.environment.empty()) environment = samples::loadEnvironment(o.environment);
  std::unique_ptr<gi::IndirectLighting> indirect;
  // Every light of the scene bounces, up to the module's limit.
  const size_t bouncing = std::min<size_t>(scene.lights.size(), gi::kMaxLights);
  if (o.indirect && (bouncing > 0 || environment))
    indirect = samples::createIndirect(ctx, o.gi, o.width, o.height, *gpuScene, scene);
  if (o.indirect && bouncing == 0)
    std::printf("indirect: %s, the scene has no light to bounce\n",
                environment ? "environment light only" : "skipped");
  if (o.indirect && bouncing < scene.lights.size())
    std::printf("indirect: the first %zu of the scene's %zu lights bounce (gi::kMaxLights)\n",
                bouncing, scene.lights.size());
  // Without a light the module still shades the environment: no light, no VSGL pass.
  gi::FrameInput input;
  if (indirect && environment) {
    samples::check(indirect->setEnvironment(
        {uint32_t(environment->width), uint32_t(environment->height), environment->pixels.data()}));
    const gi::EnvironmentSettings& e = o.gi.environment;
    if (e.method == gi::EnvironmentMethod::SgLights)
      std::printf("environment: %s, %dx%d, %u SG lights\n", o.environment.c_str(),
                  environment->width, environment->height, e.sgLightCount);
    else
      std::printf("environment: %s, %dx%d, FIS with %u samples per pixel\n", o.environment.c_str(),
                  environment->width, environment->height, e.sampleCount);
  }

  engine::GpuProfiler profiler(ctx);
  render::PassTable passTimes;
  gi::FrameOutput output;
  // The host numbers what it renders, so that the module can keep what did not change
  // (gi::FrameInput::gbufferGeneration, sceneGeneration; docs/techniques/reuse.md). The motion
  // moves the camera, a light or a box: a moved box is a new scene (setScene).
  uint64_t gbufferGeneration = 0;
  const uint32_t sequence = o.warmup + o.frames;
  for (uint32_t frame = 0; frame < sequence; ++frame) {
    const samples::Frame f =
        samples::makeFrame(scene, o.motion, frame, sequence, o.width, o.height, nullptr);
    // A swept light changes the host's direct light, not the G-buffer.
    if (frame == 0 || f.view.viewProj != view.viewProj || o.motion == samples::Motion::Move)
      ++gbufferGeneration;
    view = f.view;
    if (o.motion == samples::Motion::Move) {  // every earlier frame has completed
      gpuScene = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx, f.scene));
      if (indirect) samples::check(indirect->setScene(samples::sceneGeometry(*gpuScene, f.scene)));
    }
    if (o.motion == samples::Motion::Sweep) host.setLights(ctx, f.scene);
    if (indirect) {
      input = samples::frameInput(host.gbuffer(), view,
                                  std::span<const engine::Light>(f.scene.lights.data(), bouncing));
      input.gbufferGeneration = gbufferGeneration;
      input.sceneGeneration = 1;  // the scene's buffers never change in place here
    }
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      profiler.beginFrame(cmd);
      engine::ProfileScope total(&profiler, cmd, "host frame");
      host.recordGBuffer(cmd, *gpuScene, view, &profiler);
      if (indirect) samples::check(indirect->record(cmd, input, &output));
      // The direct light after the module, so that it can shadow with the module's light views.
      host.recordDirectLight(cmd, *gpuScene, view, &profiler,
                             o.shadowsFromModule ? std::span(output.lightViews)
                                                 : std::span<const gi::LightViewOutput>());
    });
    if (frame < o.warmup) continue;  // lavapipe compiles pipelines at their first dispatch
    // A pass that did not run in a frame (kept from an earlier one) counts 0 there.
    passTimes.beginFrame();
    for (const auto& pass : profiler.results()) passTimes.add(pass.name, pass.ms, pass.dispatches);
    if (indirect)
      for (const auto& pass : indirect->lastFrameTimes())
        passTimes.add("gi " + pass.name, pass.ms, pass.dispatches);
  }
  // Adaptive shading's work in the last frame: texels shaded per level instead of every pixel.
  const gi::ShadingCounts counts = indirect ? indirect->lastShadingCounts() : gi::ShadingCounts{};
  uint32_t shaded = o.width * o.height;
  if (counts.adaptive)
    shaded = counts.shaded[0] + counts.shaded[1] + counts.shaded[2] + counts.shaded[3];
  passTimes.print(indirect ? o.gi.vsglCount : 0, shaded);
  if (o.shadowsFromModule)
    std::printf(
        "shadows: %u shadow views are the module's light views (%u^2), the rest the host's\n",
        host.shadowedByModule(), render::shadowResolutionFor(o));
  // The effect planner's decisions for the last frame: what it left out, and why.
  if (indirect) {
    for (const std::string& reason : indirect->lastPlan().reasons)
      std::printf("plan: %s\n", reason.c_str());
    for (const std::string& reason : indirect->lastPlan().reuse.reasons)
      std::printf("%s\n", reason.c_str());
    if (indirect->lastPlan().reuse.shading && o.motion == samples::Motion::Static)
      std::printf(
          "reuse: a still view: the measured frames kept the warm-up frame's work (the gi rows "
          "are 0); --reuse off or --motion orbit|sweep|move times the passes\n");
  }
  if (counts.adaptive) {
    const uint32_t surface = o.width * o.height - counts.skyPixels;
    std::printf("adaptive shading: %u texels shaded for %u surface pixels (%.1f %%); per level:",
                shaded, surface, 100.0 * shaded / std::max(surface, 1u));
    for (uint32_t level = 0; level < counts.shaded.size(); ++level)
      std::printf(
          " L%u %u shaded (%u without glossy), %u interpolated, %u reused, light of %.1f %% of the "
          "pixels;",
          level, counts.shaded[level], counts.shadedWithoutGlossy[level],
          counts.interpolated[level], counts.reused[level],
          100.0 * counts.pixelsFrom[level] / std::max(surface, 1u));
    std::printf("\n");
  }
  if (indirect && indirect->lastPlan().culled) {
    uint64_t tests = 0, skipped = 0;
    for (uint32_t level = 0; level < counts.vsglTests.size(); ++level) {
      tests += counts.vsglTests[level];
      skipped += counts.vsglsSkipped[level];
    }
    std::printf(
        "vsgl culling: %llu of %llu subgroup x VSGL tests skipped (%.1f %%)\n",
        static_cast<unsigned long long>(skipped), static_cast<unsigned long long>(tests),
        100.0 * static_cast<double>(skipped) / static_cast<double>(std::max<uint64_t>(tests, 1)));
  }
  // The machine's FMA and memory peaks in the same run, to read the pass times against
  // (benchmarks report fractions of them; absolute times on a shared machine drift).
  const engine::FmaPeak peak = engine::measureFmaPeak(ctx);
  std::printf("device FMA peak (measured now): %.1f GFLOP/s\n", peak.gflops);
  const engine::BandwidthPeak bandwidth = engine::measureBandwidthPeak(ctx);
  std::printf("device memory bandwidth (copy, measured now): %.1f GB/s\n", bandwidth.gbPerSecond);

  std::string base = (std::filesystem::path(o.outDir) / stem).string();
  // Built-in scenes exist only as code; a .gltf copy lets other tools open the same scene.
  if (samples::isBuiltinScene(o.scene)) engine::writeGltf(scene, base + ".gltf");
  samples::FrameImages frame = samples::readFrame(ctx, host, indirect ? &output : nullptr, view,
                                                  environment ? &*environment : nullptr);
  const engine::ImageRgba32f& image = frame.final;
  engine::ToneMapSettings toneMap{o.exposureEv};
  if (frame.bounced) {
    engine::ImageRgba32f only = frame.diffuse;
    samples::addInto(only, frame.glossy);
    samples::writePair(base + "_indirect", only, toneMap);
    std::vector<uint8_t> frameRgba = engine::toneMap(image, toneMap);
    std::vector<gpu::Vsgl> vsgls = samples::readVsgls(ctx, output);
    engine::writePng(
        base + "_vsgls.png", image.width, image.height,
        samples::drawVsglLobes(frameRgba, image.width, image.height, vsgls, view.viewProj));
    if (output.shadingLevels.image) {
      engine::writePng(
          base + "_levels.png", image.width, image.height,
          samples::levelColours(frameRgba, samples::readR32f(ctx, output.shadingLevels, o.width,
                                                             o.height, "shading-level map")));
      std::printf(
          "wrote %s_levels.png (adaptive shading: the level each pixel's light was "
          "shaded at)\n",
          base.c_str());
    }
    if (o.gi.ismEnabled) {
      // One more frame with the chosen VSGL's visibility written out.
      const uint32_t k = o.debugVsgl >= 0 ? uint32_t(o.debugVsgl) : samples::brightestVsgl(vsgls);
      gi::Settings debug = indirect->settings();
      debug.debugVsgl = int32_t(k);
      samples::check(indirect->setSettings(debug));
      ctx.submitAndWait(
          [&](VkCommandBuffer cmd) { samples::check(indirect->record(cmd, input, &output)); });
      engine::writePng(base + "_visibility.png", image.width, image.height,
                       samples::greyscale(samples::readR32f(ctx, output.debugVisibility, o.width,
                                                            o.height, "debug visibility")));
      std::printf("wrote %s_visibility.png (ISM visibility of VSGL %u)\n", base.c_str(), k);
    }
  }
  if (frame.environmentLit)
    samples::writePair(base + "_environment", frame.environmentLight, toneMap);
  samples::writePair(base, image, toneMap);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  std::printf(
      "wrote %s.exr (linear) and %s.png (exposure x%.3g, ACES filmic, sRGB)%s in %.2f s "
      "wall\n",
      base.c_str(), base.c_str(), engine::exposureScale(image, toneMap),
      indirect
          ? (output.environmentDiffuse.image ? ", _indirect, _environment.{exr,png}, _vsgls.png"
                                             : ", _indirect.{exr,png}, _vsgls.png")
          : "",
      wall);
  return samples::validationExitStatus(ctx, "vsgl_render");
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_render", [&] { return run(render::parseOptions(argc, argv)); });
}
