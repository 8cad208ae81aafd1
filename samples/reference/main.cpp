// vsgl_reference: the one-bounce ground truth of a scene (gi/truth/path_tracer.h), rendered on
// the CPU with Embree for the camera and light the sample renderer uses, written as linear EXRs
// (direct, indirect = diffuse + glossy, each lobe apart, and the per-pixel standard error) and a
// tone-mapped PNG of direct + indirect.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string_view>

#include "cli_values.h"
#include "default_light.h"
#include "embree_scene.h"
#include "engine/error.h"
#include "engine/image_metrics.h"
#include "gi_host.h"
#include "path_tracer.h"
#include "program_exit.h"
#include "scene_files.h"
#include "vpl_gather.h"

namespace {

struct Options {
  std::string scene = "cornell";
  std::string outDir = "out";
  uint32_t width = 640;
  uint32_t height = 360;
  truth::PathTraceSettings trace;
  std::string cacheDir;  // "" = <out>/cache
  bool cache = true;
  uint32_t vplRsm = 0;  // 0 = no VPL gather
  std::string compare;  // an image to score against the reference's indirect light
  samples::LightChoice light = samples::LightChoice::Auto;
  std::string camera;  // "" = the first
  bool help = false;
};

const char* usage() {
  return "usage: vsgl_reference [options]\n"
         "  --scene NAME|FILE    built-in scene (cornell, atrium, checker, lounge) or .gltf/.glb "
         "(default "
         "cornell)\n"
         "  --out DIR            output directory (default out)\n"
         "  --width N --height N image size in pixels, 1..8192 (default "
         "640x360)\n" SAMPLES_LIGHT_USAGE SAMPLES_CAMERA_USAGE
         "  --noise R            stop a pixel when its standard error is R of its value,\n"
         "                       0.001..0.5 (default 0.01), or R/10 of the image's mean\n"
         "  --max-samples N      per pixel, 16..1048576 (default 65536)\n"
         "  --threads N          0 = every core (default 0)\n"
         "  --seed N             random seed (default 1)\n"
         "  --cache DIR          reference cache (default <out>/cache); --no-cache renders anew\n"
         "  --vpl N              also gather every texel of an N^2 RSM as a VPL, 16..1024,\n"
         "                       and score it against the path tracer\n"
         "  --compare FILE       score an indirect-light image (e.g. vsgl_render's\n"
         "                       <scene>_indirect.exr) against the path tracer\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  o.trace.progress = true;
  for (samples::Arguments args(argc, argv); args.next();) {
    const std::string_view arg = args.option();
    if (arg == "--scene")
      o.scene = args.value();
    else if (arg == "--light")
      o.light = samples::parseLightChoice(arg, args.value());
    else if (arg == "--camera")
      o.camera = args.value();
    else if (arg == "--out")
      o.outDir = args.value();
    else if (arg == "--width")
      o.width = samples::parseUint(arg, args.value(), 1, 8192);
    else if (arg == "--height")
      o.height = samples::parseUint(arg, args.value(), 1, 8192);
    else if (arg == "--noise")
      o.trace.relativeError = samples::parseFloat(arg, args.value(), 0.001f, 0.5f);
    else if (arg == "--max-samples")
      o.trace.maxSamples = samples::parseUint(arg, args.value(), 16, 1u << 20);
    else if (arg == "--threads")
      o.trace.threads = samples::parseUint(arg, args.value(), 0, 1024);
    else if (arg == "--seed")
      o.trace.seed = samples::parseUint(arg, args.value(), 0, 0xFFFFFFFFu);
    else if (arg == "--cache")
      o.cacheDir = args.value();
    else if (arg == "--no-cache")
      o.cache = false;
    else if (arg == "--vpl")
      o.vplRsm = samples::parseUint(arg, args.value(), 16, 1024);
    else if (arg == "--compare")
      o.compare = args.value();
    else if (arg == "--help" || arg == "-h")
      o.help = true;
    else
      throw engine::Error(std::string(arg) + ": unknown option (see --help)");
  }
  o.trace.minSamples = std::min(o.trace.minSamples, o.trace.maxSamples);
  return o;
}

// RMSE, relative MSE and PSNR of `test` against the reference's indirect light, and a
// false-colour picture of the error (scale: the 99th percentile of the absolute error).
void printScore(const std::string& name, const std::vector<glm::dvec3>& test,
                const std::vector<glm::dvec3>& reference, const std::string& png, uint32_t w,
                uint32_t h) {
  const engine::ErrorMetrics m = engine::compareImages(test, reference);
  const double scale = engine::percentileAbsError(test, reference, 0.99);
  engine::writeFalseColourError(png, int(w), int(h), test, reference, scale);
  std::printf(
      "%s against the path tracer: RMSE %.4g (%.2f %% of the mean %.4g), relMSE %.4g, "
      "PSNR %.2f dB%s; error picture %s (0..%.3g)\n",
      name.c_str(), m.rmse, 100.0 * m.rmse / m.referenceMean, m.referenceMean, m.relativeMse,
      m.psnr, m.nonFinite ? ", NON-FINITE PIXELS" : "", png.c_str(), scale);
}

int run(const Options& o) {
  if (o.help) {
    std::printf("%s", usage());
    return 0;
  }
  engine::Scene scene = samples::loadScene(o.scene);
  samples::selectCamera(scene, o.camera);
  const std::string lightNote =
      samples::applyLightChoice(scene, o.light, false, float(o.width) / float(o.height));
  if (!lightNote.empty()) std::printf("%s\n", lightNote.c_str());
  const std::vector<uint32_t> lights = samples::bouncingLights(scene);
  const engine::View view = samples::sceneView(scene, o.width, o.height);
  samples::createOutputDirectory(o.outDir);
  std::printf("scene: %s, %u triangles, %ux%u, %zu lights bounce, noise target %.3g\n",
              scene.source.c_str(), scene.triangleCount(), o.width, o.height, lights.size(),
              o.trace.relativeError);
  bool fromCache = false;
  const truth::PathTraceImage r =
      o.cache ? truth::cachedPathTrace(
                    truth::ReferenceCache(o.cacheDir.empty()
                                              ? (std::filesystem::path(o.outDir) / "cache").string()
                                              : o.cacheDir),
                    scene, view, lights, o.trace, &fromCache)
              : truth::pathTrace(scene, truth::EmbreeScene(scene), view, lights, o.trace);
  if (fromCache) std::printf("reference from the cache (rendered in %.1f s)\n", r.seconds);
  uint64_t samples = 0, pixels = 0;
  for (uint32_t n : r.samples)
    if (n > 0) {
      samples += n;
      ++pixels;
    }
  std::printf(
      "traced %.1f s: %.0f samples per pixel on average; standard error / target: "
      "median %.2f, 95th percentile %.2f; noise floor %.3g W/(sr m^2)\n",
      r.seconds, pixels ? double(samples) / double(pixels) : 0.0, r.medianErrorRatio,
      r.p95ErrorRatio, r.noiseFloor);

  const std::string base =
      (std::filesystem::path(o.outDir) / std::filesystem::path(o.scene).stem()).string() +
      "_reference";
  const uint32_t w = r.width, h = r.height;
  const engine::ToneMapSettings toneMap{};
  samples::writePair(
      base,
      samples::imageFrom(w, h, [&](size_t i) { return r.direct[i] + r.diffuse[i] + r.glossy[i]; }),
      toneMap);
  engine::writeExr(base + "_direct.exr",
                   samples::imageFrom(w, h, [&](size_t i) { return r.direct[i]; }));
  engine::writeExr(base + "_indirect.exr",
                   samples::imageFrom(w, h, [&](size_t i) { return r.diffuse[i] + r.glossy[i]; }));
  engine::writeExr(base + "_diffuse.exr",
                   samples::imageFrom(w, h, [&](size_t i) { return r.diffuse[i]; }));
  engine::writeExr(base + "_glossy.exr",
                   samples::imageFrom(w, h, [&](size_t i) { return r.glossy[i]; }));
  engine::writeExr(base + "_stderr.exr", samples::imageFrom(w, h, [&](size_t i) {
                     return glm::dvec3(r.standardError[i]);
                   }));
  std::printf("wrote %s.{exr,png}, _direct, _indirect, _diffuse, _glossy, _stderr .exr\n",
              base.c_str());

  std::vector<glm::dvec3> indirect(r.diffuse.size());
  for (size_t i = 0; i < indirect.size(); ++i) indirect[i] = r.diffuse[i] + r.glossy[i];
  if (o.vplRsm > 0) {
    const truth::EmbreeScene rays(scene);
    const std::vector<truth::Vpl> vpls = truth::rsmVpls(scene, rays, lights, o.vplRsm);
    const truth::VplGatherImage g = truth::vplGather(scene, rays, view, vpls, o.trace.threads);
    std::vector<glm::dvec3> gathered(indirect.size());
    for (size_t i = 0; i < gathered.size(); ++i) gathered[i] = g.diffuse[i] + g.glossy[i];
    engine::writeExr(base + "_vpl.exr",
                     samples::imageFrom(w, h, [&](size_t i) { return gathered[i]; }));
    printScore("VPL gather (RSM " + std::to_string(o.vplRsm) + "^2, " + std::to_string(g.vplCount) +
                   " VPLs, " + std::to_string(g.seconds) + " s)",
               gathered, indirect, base + "_vpl_error.png", w, h);
  }
  if (!o.compare.empty()) {
    const engine::ImageRgba32f image = engine::readImage(o.compare);
    if (uint32_t(image.width) != w || uint32_t(image.height) != h)
      throw engine::Error(o.compare + ": " + std::to_string(image.width) + "x" +
                          std::to_string(image.height) + " image, the reference is " +
                          std::to_string(w) + "x" + std::to_string(h));
    std::vector<glm::dvec3> test(indirect.size());
    for (size_t i = 0; i < test.size(); ++i)
      test[i] = glm::dvec3(image.pixels[4 * i], image.pixels[4 * i + 1], image.pixels[4 * i + 2]);
    printScore(
        o.compare, test, indirect,
        (std::filesystem::path(o.outDir) / std::filesystem::path(o.compare).stem()).string() +
            "_error.png",
        w, h);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_reference", [&] { return run(parseOptions(argc, argv)); });
}
