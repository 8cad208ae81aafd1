// vsgl_flicker: temporal-flicker captures (docs/flicker.md). One animated sequence (motion.h) of
// a scene, rendered by every method through the public API, as a host would, and by a CPU
// reference. The methods keep their state from frame to frame (k-means starts from its previous
// centres), and each first renders --warmup frames of the first frame, so that the capture sees
// them in their steady state. Two flicker figures per frame and method:
//   - image flicker: engine::temporalError of the indirect light's 8 x 8 block means against the
//     reference's (change the reference does not show), the previous frame reprojected when the
//     camera moves (reprojection.h);
//   - VSGL power change: sum over VSGLs i of |Phi_i(t) - Phi_i(t-1)| over sum of Phi_i(t-1)
//     (luminance; VSGL i is lattice point i, or k-means cluster i).
// It writes numbered EXR/PNG frames per method, a preview strip, an animated GIF, flicker.csv
// and flicker_summary.{json,csv}.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli_values.h"
#include "default_light.h"
#include "engine/gbuffer.h"
#include "engine/gbuffer_reference.h"
#include "engine/image_metrics.h"
#include "engine/profiler.h"
#include "engine/rasterizer.h"
#include "engine/tonemap.h"
#include "gi_host.h"
#include "motion.h"
#include "path_tracer.h"
#include "preview.h"
#include "program_exit.h"
#include "reference_cache.h"
#include "reprojection.h"
#include "scene_files.h"
#include "vpl_gather.h"

namespace {

using nlohmann::json;

struct Options {
  std::string scene = "checker";
  std::string motion = "orbit";
  std::string path;  // --path FILE: the recorded view path of --motion path
  uint32_t frames = 16;
  bool framesGiven = false;  // a path sets the frame count; an explicit one must agree with it
  uint32_t width = 160, height = 90;
  uint32_t count = 128;
  uint32_t block = 8;
  uint32_t warmup = 64;
  bool reuse = true;  // gi::Settings::reuse of every method
  std::vector<std::string> methods = {"tok15", "modified", "modified-k4", "kmeans-2d", "kmeans-3d"};
  std::string pdf = "brsm";
  std::string reference = "vpl";
  uint32_t vplRsm = 32;
  float noise = 0.05f;
  std::string outDir = "flicker";
  samples::LightChoice light = samples::LightChoice::Auto;
  bool lightGiven = false;
  std::string camera;             // "" = the first
  samples::CommonOptions common;  // --device, --validation, --help
};

const char* usage() {
  return "usage: vsgl_flicker [options]\n"
         "  --scene NAME|FILE  built-in scene (cornell, atrium, checker, lounge) or .gltf/.glb "
         "(default "
         "checker)\n"
         "  --motion M         static, orbit (camera), sweep (light), move (a box) or path (a\n"
         "                     recorded view path) (default orbit)\n"
         "  --path FILE        the view path --motion path replays (vsgl_viewer records it): its\n"
         "                     cameras and lights, which replace the scene's (--light is not\n"
         "                     applied); the sequence has its frames\n" SAMPLES_LIGHT_USAGE
             SAMPLES_CAMERA_USAGE
         "  --frames N         frames in the sequence, 2..1000 (default 16; with --path, the\n"
         "                     file's)\n"
         "  --width N --height N  image size, 1..4096 (default 160x90)\n"
         "  --count N          VSGLs, 1..32768 (default 128)\n"
         "  --reuse on|off     reuse across frames in every method (default on; the summary's\n"
         "                     frame_ms is the module's median GPU time per frame after the\n"
         "                     first, docs/techniques/reuse.md)\n"
         "  --warmup N         frames of the first frame each method renders first, 0..1000\n"
         "                     (default 64: k-means converges from its seeds)\n"
         "  --block N          the image flicker compares N x N pixel block means, 1..64 (1 =\n"
         "                     per pixel; default 8)\n"
         "  --methods LIST     comma-separated: tok15, modified, kmeans-2d, kmeans-3d, vpl; a "
         "filtered\n"
         "                     method takes a kernel scale as -kK (modified-k4); modified-full\n"
         "                     shades every pixel (adaptive shading off) (default\n"
         "                     tok15,modified,modified-k4,kmeans-2d,kmeans-3d)\n"
         "  --pdf KIND         brsm (view-dependent) or flux (default brsm)\n"
         "  --reference KIND   vpl (brute-force VPL gather, exact visibility) or path (path\n"
         "                     tracer, cached under <out>/cache) (default vpl)\n"
         "  --vpl-rsm N        the VPL gather's RSM side, 16..512 (default 32)\n"
         "  --noise R          the path tracer's relative standard error, 0.001..0.5 (default "
         "0.05)\n"
         "  --out DIR          output directory (default flicker)\n"
         "  --device SEL       Vulkan device index or name substring\n"
         "  --validation       enable the Khronos validation layer\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (samples::Arguments args(argc, argv); args.next();) {
    const std::string_view arg = args.option();
    if (arg == "--scene")
      o.scene = args.value();
    else if (arg == "--light") {
      o.light = samples::parseLightChoice(arg, args.value());
      o.lightGiven = true;
    } else if (arg == "--camera")
      o.camera = args.value();
    else if (arg == "--motion")
      o.motion = args.value();
    else if (arg == "--path")
      o.path = args.value();
    else if (arg == "--frames") {
      o.frames = samples::parseUint(arg, args.value(), 2, 1000);
      o.framesGiven = true;
    } else if (arg == "--width")
      o.width = samples::parseUint(arg, args.value(), 1, 4096);
    else if (arg == "--height")
      o.height = samples::parseUint(arg, args.value(), 1, 4096);
    else if (arg == "--count")
      o.count = samples::parseUint(arg, args.value(), 1, gi::kMaxVsglCount);
    else if (arg == "--warmup")
      o.warmup = samples::parseUint(arg, args.value(), 0, 1000);
    else if (arg == "--reuse")
      o.reuse = samples::parseChoice<bool>(arg, args.value(), {{"on", true}, {"off", false}});
    else if (arg == "--block")
      o.block = samples::parseUint(arg, args.value(), 1, 64);
    else if (arg == "--methods")
      o.methods = samples::parseList(arg, args.value());
    else if (arg == "--pdf")
      o.pdf = samples::parseChoice<std::string>(arg, args.value(),
                                                {{"brsm", "brsm"}, {"flux", "flux"}});
    else if (arg == "--reference")
      o.reference =
          samples::parseChoice<std::string>(arg, args.value(), {{"vpl", "vpl"}, {"path", "path"}});
    else if (arg == "--vpl-rsm")
      o.vplRsm = samples::parseUint(arg, args.value(), 16, 512);
    else if (arg == "--noise")
      o.noise = samples::parseFloat(arg, args.value(), 0.001f, 0.5f);
    else if (arg == "--out")
      o.outDir = args.value();
    else
      samples::parseCommonOption(arg, args, o.common);
  }
  if (o.outDir.empty()) throw engine::Error("--out: empty path");
  if (o.motion == "path" && o.path.empty())
    throw engine::Error("--motion path: needs --path FILE (the view path to replay)");
  if (o.motion != "path" && !o.path.empty())
    throw engine::Error("--path: only with --motion path (not --motion " + o.motion + ")");
  if (o.block > std::min(o.width, o.height))
    throw engine::Error("--block: " + std::to_string(o.block) + " is larger than the image");
  return o;
}

// A --methods word as module settings: "<method>" or, for tok15 and modified, "<method>-k<K>".
gi::Settings methodSettings(const std::string& word, const Options& o) {
  gi::Settings s;
  s.vsglCount = o.count;
  s.brsm.gridSize = std::min(s.brsm.gridSize, s.rsmSize);
  s.pdf = o.pdf == "flux" ? gi::PdfKind::Flux : gi::PdfKind::Brsm;
  std::string method = word;
  if (const size_t k = word.find("-k"); k != std::string::npos && word.rfind("kmeans", 0) != 0) {
    method = word.substr(0, k);
    s.kernelScale = samples::parseFloat("--methods", word.substr(k + 2), 1.0f, float(o.count));
  }
  if (method == "modified-full") {  // every pixel shaded: adaptive shading's own flicker
    method = "modified";
    s.adaptive.enabled = false;
  }
  if (method == "tok15")
    s.rule = gi::KernelRule::Tok15;
  else if (method == "kmeans-2d")
    s.method = gi::VsglMethod::KmeansImage;
  else if (method == "kmeans-3d")
    s.method = gi::VsglMethod::KmeansWorld;
  else if (method == "vpl")
    s.method = gi::VsglMethod::Vpl;
  else if (method != "modified")
    throw engine::Error(
        "--methods: '" + word +
        "' is not one of tok15, modified (each with an optional -kK), modified-full, "
        "kmeans-2d, kmeans-3d, vpl");
  if (std::string bad = gi::validateSettings(s); !bad.empty()) throw engine::Error(bad);
  return s;
}

// Per VSGL, the luminance of both lobes' power.
std::vector<double> vsglPowers(const std::vector<gpu::Vsgl>& vsgls) {
  std::vector<double> power;
  for (const gpu::Vsgl& v : vsgls) power.push_back(double(v.diffuse.power.a) + v.specular.power.a);
  return power;
}

double powerChange(const std::vector<double>& previous, const std::vector<double>& current) {
  double change = 0.0, total = 0.0;
  for (size_t i = 0; i < current.size(); ++i) {
    change += std::abs(current[i] - previous[i]);
    total += previous[i];
  }
  return total > 0.0 ? change / total : change;
}

// The image flicker figure: engine::temporalError over o.block x o.block block means of the
// reprojected previous frame and this one, for the method and the reference alike.
double blockFlicker(const std::vector<glm::dvec3>& previous, const std::vector<glm::dvec3>& current,
                    const std::vector<glm::dvec3>& previousReference,
                    const std::vector<glm::dvec3>& currentReference,
                    const std::vector<uint8_t>& valid, const Options& o) {
  auto means = [&](const std::vector<glm::dvec3>& image) {
    return engine::blockMeans(image, o.width, o.height, o.block, valid);
  };
  const engine::BlockMeans p = means(previous), c = means(current);
  return engine::temporalError(p.means, c.means, means(previousReference).means,
                               means(currentReference).means, c.valid);
}

struct Capture {
  std::string name;
  std::unique_ptr<gi::IndirectLighting> lighting;
  std::vector<glm::dvec3> previous;
  std::vector<double> previousPower;
  double flickerSum = 0.0, powerChangeSum = 0.0, relativeMseSum = 0.0;
  std::vector<double> frameMs;                // the module's GPU time in each frame after the first
  std::vector<std::vector<uint8_t>> preview;  // tone-mapped, at the previewFrames
};

// The recorded frames of --path, checked before any work: the sequence takes their count, and
// every frame must have a light to bounce (the path's lights replace the scene's).
std::vector<samples::PathFrame> readPath(Options& o) {
  std::vector<samples::PathFrame> path = samples::readViewPath(o.path);
  const auto count = static_cast<uint32_t>(path.size());
  if (o.framesGiven && o.frames != count)
    throw engine::Error("--frames " + std::to_string(o.frames) + ": --path " + o.path + " has " +
                        std::to_string(count) + " frames");
  if (count < 2) throw engine::Error("--path " + o.path + ": 1 frame; a capture needs 2 at least");
  o.frames = count;
  for (uint32_t t = 0; t < count; ++t) {
    const size_t n = path[t].lights.size();
    if (n == 0 || n > gi::kMaxLights)
      throw engine::Error("--path " + o.path + ": frame " + std::to_string(t) + " has " +
                          std::to_string(n) + " lights; the module bounces 1 to " +
                          std::to_string(gi::kMaxLights));
  }
  return path;
}

int run(Options o) {
  if (o.common.help) {
    std::printf("%s", usage());
    return 0;
  }
  const samples::Motion motion = samples::parseMotion(o.motion);
  std::vector<samples::PathFrame> path;
  if (motion == samples::Motion::Path) path = readPath(o);
  engine::Scene base = samples::loadScene(o.scene);
  samples::selectCamera(base, o.camera);
  if (motion == samples::Motion::Path) {
    if (o.lightGiven)
      std::printf("--light: not applied: the lights recorded in %s replace the scene's\n",
                  o.path.c_str());
  } else {
    const std::string lightNote =
        samples::applyLightChoice(base, o.light, false, float(o.width) / float(o.height));
    if (!lightNote.empty()) std::printf("%s\n", lightNote.c_str());
    samples::bouncingLights(base);  // fails before any work
  }
  if (motion == samples::Motion::Sweep) samples::sweptLight(base);  // fails before any work
  std::vector<gi::Settings> settings;
  for (const std::string& word : o.methods) {
    settings.push_back(methodSettings(word, o));
    settings.back().reuse = o.reuse;
  }
  const std::filesystem::path out(o.outDir);
  samples::createOutputDirectory(o.outDir);
  for (const std::string& name : o.methods) samples::createOutputDirectory((out / name).string());
  samples::createOutputDirectory((out / "reference").string());
  const truth::ReferenceCache cache((out / "cache").string());

  engine::Context ctx({o.common.validation, o.common.device});
  engine::Rasterizer rasterizer(ctx);
  engine::GBufferResolve resolve(ctx);
  engine::GBuffer gbuffer = engine::createGBuffer(ctx, o.width, o.height);
  engine::Buffer visibility(ctx, engine::Rasterizer::visibilityBytes(o.width, o.height),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  std::unique_ptr<engine::SceneGpu> gpuScene;
  std::vector<Capture> captures;  // after the context: the modules go before the device does
  const std::vector<uint32_t> kept = flicker::previewFrames(o.frames);
  flicker::Preview preview{int(o.width), int(o.height), {{"reference", {}}}};
  std::vector<glm::dvec3> previousReference;
  engine::GBufferData previousGBuffer;
  engine::View previousView;
  engine::ToneMapSettings toneMap;  // one exposure for the whole capture: set from frame 0
  std::ofstream csv(out / "flicker.csv");
  csv << "frame,method,image_flicker,vsgl_power_change,relative_mse\n";

  // The G-buffer's number (gi::FrameInput::gbufferGeneration): a new one when the camera or
  // the scene moved, so that each module keeps what did not change (--reuse).
  uint64_t gbufferGeneration = 0;
  for (uint32_t t = 0; t < o.frames; ++t) {
    const samples::Frame f = samples::makeFrame(base, motion, t, o.frames, o.width, o.height,
                                                motion == samples::Motion::Path ? &path : nullptr);
    if (t == 0 || f.view.viewProj != previousView.viewProj || motion == samples::Motion::Move)
      ++gbufferGeneration;
    const std::vector<uint32_t> lights = samples::bouncingLights(f.scene);  // a path's vary
    if (!gpuScene || motion == samples::Motion::Move)  // every earlier submission has completed
      gpuScene = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx, f.scene));
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      rasterizer.record(cmd, *gpuScene, f.view.viewProj, {&visibility, 0, o.width, o.height});
      resolve.record(cmd, *gpuScene, visibility, f.view, gbuffer);
    });

    // The reference of this frame.
    std::vector<glm::dvec3> reference(size_t{o.width} * o.height);
    if (o.reference == "vpl") {
      const truth::EmbreeScene rays(f.scene);
      const truth::VplGatherImage g =
          truth::vplGather(f.scene, rays, f.view, truth::rsmVpls(f.scene, rays, lights, o.vplRsm));
      for (size_t i = 0; i < reference.size(); ++i) reference[i] = g.diffuse[i] + g.glossy[i];
    } else {
      truth::PathTraceSettings trace;
      trace.relativeError = o.noise;
      const truth::PathTraceImage p = truth::cachedPathTrace(cache, f.scene, f.view, lights, trace);
      for (size_t i = 0; i < reference.size(); ++i) reference[i] = p.diffuse[i] + p.glossy[i];
    }
    const engine::ImageRgba32f referenceImage =
        samples::imageFrom(o.width, o.height, [&](size_t i) { return reference[i]; });
    if (t == 0) toneMap.exposureEv = std::log2(engine::exposureScale(referenceImage, toneMap));
    char stem[32];
    std::snprintf(stem, sizeof(stem), "frame_%04u", t);
    samples::writePair((out / "reference" / stem).string(), referenceImage, toneMap);
    const bool previewed = std::binary_search(kept.begin(), kept.end(), t);
    if (previewed) preview.rows[0].frames.push_back(engine::toneMap(referenceImage, toneMap));

    // The previous frame seen from this one (identity unless the camera moved).
    const engine::GBufferData decoded = engine::readbackGBuffer(ctx, gbuffer);
    flicker::Reprojection reprojection;
    std::vector<glm::dvec3> previousReferenceAligned;
    if (t > 0) {
      reprojection = flicker::reproject(previousGBuffer, previousView, decoded, f.view);
      previousReferenceAligned = flicker::resample(previousReference, reprojection);
    }
    gi::FrameInput input = samples::frameInput(gbuffer, f.view, f.scene.lights);
    input.gbufferGeneration = gbufferGeneration;
    input.sceneGeneration = 1;  // a moved box is a new scene (setScene)
    for (size_t m = 0; m < o.methods.size(); ++m) {
      if (t == 0) {
        captures.push_back({o.methods[m], samples::createIndirect(ctx, settings[m], o.width,
                                                                  o.height, *gpuScene, f.scene)});
      } else if (motion == samples::Motion::Move) {
        samples::check(captures[m].lighting->setScene(samples::sceneGeometry(*gpuScene, f.scene)));
      }
      Capture& c = captures[m];
      gi::FrameOutput output;
      for (uint32_t w = 0; w <= (t == 0 ? o.warmup : 0); ++w)
        ctx.submitAndWait(
            [&](VkCommandBuffer cmd) { samples::check(c.lighting->record(cmd, input, &output)); });
      if (t > 0)
        for (const gi::PassTime& pass : c.lighting->lastFrameTimes())
          if (pass.name == "frame") c.frameMs.push_back(pass.ms);
      const std::vector<glm::dvec3> image =
          samples::indirectSum(samples::readIndirect(ctx, output, o.width, o.height));
      const std::vector<double> power = vsglPowers(samples::readVsgls(ctx, output));
      const double relativeMse = engine::compareImages(image, reference).relativeMse;
      c.relativeMseSum += relativeMse;
      csv << t << "," << c.name << ",";
      if (t > 0) {
        const double flicker =
            blockFlicker(flicker::resample(c.previous, reprojection), image,
                         previousReferenceAligned, reference, reprojection.valid, o);
        const double change = powerChange(c.previousPower, power);
        c.flickerSum += flicker;
        c.powerChangeSum += change;
        csv << flicker << "," << change;
      } else {
        csv << ",";
      }
      csv << "," << relativeMse << "\n";
      const engine::ImageRgba32f linear =
          samples::imageFrom(o.width, o.height, [&](size_t i) { return image[i]; });
      samples::writePair((out / c.name / stem).string(), linear, toneMap);
      if (previewed) c.preview.push_back(engine::toneMap(linear, toneMap));
      c.previous = image;
      c.previousPower = power;
    }
    previousReference = reference;
    previousGBuffer = decoded;
    previousView = f.view;
    std::printf("frame %u/%u\n", t + 1, o.frames);
    std::fflush(stdout);
  }

  // The summary: per method the mean of each figure over the frame pairs.
  json summary = {{"scene", o.scene},   {"motion", o.motion}, {"frames", o.frames},
                  {"warmup", o.warmup}, {"width", o.width},   {"height", o.height},
                  {"count", o.count},   {"pdf", o.pdf},       {"reference", o.reference},
                  {"block", o.block},   {"reuse", o.reuse},   {"methods", json::array()}};
  if (motion == samples::Motion::Path) summary["path"] = o.path;
  const double pairs = double(o.frames - 1);
  std::printf("%-14s %14s %18s %12s %14s\n", "method", "image flicker", "VSGL power change",
              "mean relMSE", "module ms");
  for (const Capture& c : captures) {
    // The median over the frames after the first (0 when the timestamps were not available).
    const double ms = c.frameMs.empty() ? 0.0 : engine::median(c.frameMs);
    summary["methods"].push_back({{"name", c.name},
                                  {"image_flicker", c.flickerSum / pairs},
                                  {"vsgl_power_change", c.powerChangeSum / pairs},
                                  {"relative_mse", c.relativeMseSum / double(o.frames)},
                                  {"frame_ms", ms}});
    std::printf("%-14s %14.6f %18.6f %12.5f %14.3f\n", c.name.c_str(), c.flickerSum / pairs,
                c.powerChangeSum / pairs, c.relativeMseSum / double(o.frames), ms);
  }
  std::ofstream(out / "flicker_summary.json") << summary.dump(2) << "\n";
  std::ofstream table(out / "flicker_summary.csv");
  table << "method,image_flicker,vsgl_power_change,relative_mse\n";
  for (const json& m : summary["methods"])
    table << m["name"].get<std::string>() << "," << m["image_flicker"] << ","
          << m["vsgl_power_change"] << "," << m["relative_mse"] << "\n";

  for (Capture& c : captures) preview.rows.push_back({c.name, std::move(c.preview)});
  flicker::writeStrip((out / "preview.png").string(), preview);
  flicker::writeGif((out / "preview.gif").string(), preview);
  std::printf(
      "wrote %s: frames per method, flicker.csv, flicker_summary.{json,csv}, "
      "preview.png, preview.gif\n",
      o.outDir.c_str());
  return samples::validationExitStatus(ctx, "vsgl_flicker");
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_flicker", [&] { return run(parseOptions(argc, argv)); });
}
