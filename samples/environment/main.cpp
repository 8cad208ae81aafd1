// vsgl_environment: the measured part of docs/techniques/environment.md. A row of GGX spheres
// (sphere_row.h), rasterised to a G-buffer, is lit by an environment through gi::EnvironmentMap
// and gi::EnvFisShade in each FIS mode (Filtered, Unfiltered, Randomised; Krivanek and Colbert,
// EGSR 2008, Fig. 1) at every sample count N; each row holds the FIS pass's GPU time (median of
// the timed frames) and the error of diffuse + glossy against a converged Monte Carlo reference
// of the TRUE environment (reference_cache.h), as in the paper's Fig. 3. Writes
// environment.{json,csv,md} (report.h) and environment_n<N>.png, the modes side by side with
// the reference.
#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "cli_values.h"
#include "engine/environments.h"
#include "engine/error.h"
#include "engine/gbuffer_reference.h"
#include "engine/image_io.h"
#include "engine/image_metrics.h"
#include "engine/rasterizer.h"
#include "engine/scene_gpu.h"
#include "engine/tonemap.h"
#include "engine/view.h"
#include "passes/env_fis.h"
#include "passes/env_map.h"
#include "passes/env_sg.h"
#include "passes/vsgl_shade.h"
#include "program_exit.h"
#include "reference/env_map_reference.h"
#include "reference/env_paraboloid.h"
#include "reference_cache.h"
#include "report.h"
#include "scene_files.h"
#include "sphere_row.h"

namespace {

using engine::Error;
using Mode = gi::EnvFisShade::Mode;
using Brdf = gi::EnvFisShade::Brdf;

// The methods of --methods: the three FIS modes and "sg", N SG lights generated from the
// environment (gi::EnvSgLights, pass 4 of the design). Their rows have the same columns; an sg
// row's time is the per-frame shading pass, its generation (once per environment and count)
// goes to setup_ms.
constexpr std::string_view kSgMethod = "sg";
struct Method {
  std::string_view name;
  Mode mode;
};
constexpr Method kFisMethods[] = {{"fis-filtered", Mode::Filtered},
                                  {"fis-unfiltered", Mode::Unfiltered},
                                  {"fis-randomised", Mode::Randomised}};

struct Options {
  std::string environment = "studio";
  uint32_t width = 384;
  uint32_t height = 128;
  uint32_t mapSize = 256;
  std::vector<uint32_t> counts{1, 2, 5, 10, 20, 40, 100, 200};
  std::vector<std::string> methods{"fis-filtered", "fis-unfiltered", "fis-randomised", "sg"};
  Brdf brdf = Brdf::Ggx;
  std::string brdfName = "ggx";
  uint32_t frames = 5;  // timed frames per row
  uint32_t warmup = 1;  // untimed frames before them (pipelines compile at the first dispatch)
  // The reference at every stride-th pixel in x and y, at 256^2 glossy and 128^2 diffuse
  // samples: at the defaults about 4 150 pixels, some 100 s on two cores, with a relative
  // standard error near 0.6 % on the studio (at 64^2 it was 4.7 %: the studio's small bright
  // lights need many lobe samples to converge).
  uint32_t stride = 2;
  environment::ReferenceSettings reference;
  std::string outDir = "out";
  samples::CommonOptions common;
};

const char* usage() {
  return "usage: vsgl_environment [options]\n"
         "  --environment E  built-in environment (sky, studio, white) or an HDR/EXR file "
         "(default studio)\n"
         "  --width W, --height H  image size, 8..4096 (default 384x128)\n"
         "  --map-size S     dual-paraboloid map texels per side, a power of two in 4..4096 "
         "(default 256)\n"
         "  --counts LIST    samples per pixel N, each 1..4096 (default 1,2,5,10,20,40,100,200)\n"
         "  --methods LIST   fis-filtered, fis-unfiltered, fis-randomised, sg (default all; sg:\n"
         "                   N SG lights from the environment, GGX only)\n"
         "  --brdf B         ggx, phong or ward (default ggx)\n"
         "  --frames N       timed frames per row, 1..1000 (default 5)\n"
         "  --warmup N       untimed frames before them, 0..100 (default 1)\n"
         "  --reference-stride K  reference at every K-th pixel in x and y, 1..64 (default 2)\n"
         "  --reference-strata G  G^2 glossy and (G/2)^2 diffuse samples per reference pixel, "
         "4..1024 (default 256)\n"
         "  --threads T      reference threads, 0..1024 (default 0: every core)\n"
         "  --out DIR        output directory (default out)\n"
         "  --device SEL     Vulkan device index or name substring (default: VSGL_DEVICE or auto)\n"
         "  --validation     enable the Khronos validation layer (any message fails the run)\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (samples::Arguments args(argc, argv); args.next();) {
    const std::string_view arg = args.option();
    if (arg == "--environment") {
      o.environment = args.value();
    } else if (arg == "--width") {
      o.width = samples::parseUint(arg, args.value(), 8, 4096);
    } else if (arg == "--height") {
      o.height = samples::parseUint(arg, args.value(), 8, 4096);
    } else if (arg == "--map-size") {
      o.mapSize = samples::parseUint(arg, args.value(), 4, 4096);
      if (!std::has_single_bit(o.mapSize))
        throw Error("--map-size: " + std::to_string(o.mapSize) + " is not a power of two");
    } else if (arg == "--counts") {
      o.counts = samples::parseUintList(arg, args.value(), 1, 4096);
    } else if (arg == "--methods") {
      o.methods.clear();
      for (const std::string& m : samples::parseList(arg, args.value())) {
        samples::parseChoice<int>(
            arg, m, {{"fis-filtered", 0}, {"fis-unfiltered", 1}, {"fis-randomised", 2}, {"sg", 3}});
        if (std::find(o.methods.begin(), o.methods.end(), m) == o.methods.end())
          o.methods.push_back(m);
      }
    } else if (arg == "--brdf") {
      const std::string_view v = args.value();
      o.brdf = samples::parseChoice<Brdf>(
          arg, v, {{"ggx", Brdf::Ggx}, {"phong", Brdf::Phong}, {"ward", Brdf::Ward}});
      o.brdfName = v;
    } else if (arg == "--frames") {
      o.frames = samples::parseUint(arg, args.value(), 1, 1000);
    } else if (arg == "--warmup") {
      o.warmup = samples::parseUint(arg, args.value(), 0, 100);
    } else if (arg == "--reference-stride") {
      o.stride = samples::parseUint(arg, args.value(), 1, 64);
    } else if (arg == "--reference-strata") {
      o.reference.glossyStrata = samples::parseUint(arg, args.value(), 4, 1024);
      o.reference.diffuseStrata = o.reference.glossyStrata / 2;
    } else if (arg == "--threads") {
      o.reference.threads = samples::parseUint(arg, args.value(), 0, 1024);
    } else if (arg == "--out") {
      o.outDir = args.value();
    } else {
      samples::parseCommonOption(arg, args, o.common);
    }
  }
  std::sort(o.counts.begin(), o.counts.end());
  o.counts.erase(std::unique(o.counts.begin(), o.counts.end()), o.counts.end());
  if (o.outDir.empty()) throw Error("--out: empty path");
  if (o.brdf != Brdf::Ggx &&
      std::find(o.methods.begin(), o.methods.end(), kSgMethod) != o.methods.end())
    throw Error("--methods: sg shades GGX only, not --brdf " + o.brdfName);
  return o;
}

// A built-in environment by name (at 4 equirect texels per map texel along the equator, at
// least 1024 wide), else an image file; errors name the option.
engine::ImageRgba32f loadEnvironment(const Options& o) {
  return samples::loadEnvironment(o.environment, std::clamp(4u * o.mapSize, 1024u, 16384u));
}

// A file-name-safe word for the environment (the reference cache's name).
std::string environmentStem(const std::string& environment) {
  std::string stem = std::filesystem::path(environment).stem().string();
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
  return stem.empty() ? "environment" : stem;
}

std::vector<glm::dvec3> sumOf(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
  std::vector<glm::dvec3> out(a.size());
  for (size_t i = 0; i < a.size(); ++i) out[i] = glm::dvec3(a[i]) + glm::dvec3(b[i]);
  return out;
}

engine::ImageRgba32f toImage(const std::vector<glm::dvec3>& rgb, uint32_t width, uint32_t height) {
  engine::ImageRgba32f image{int(width), int(height), {}};
  image.pixels.reserve(rgb.size() * 4);
  for (const glm::dvec3& c : rgb)
    image.pixels.insert(image.pixels.end(), {float(c.r), float(c.g), float(c.b), 1.0f});
  return image;
}

// The panels stacked top to bottom, one exposure for all, separated by dark grey rows.
void writePicture(const std::string& path, const std::vector<engine::ImageRgba32f>& panels,
                  float exposureEv) {
  constexpr int kSeparator = 3;  // pixels
  const int width = panels.at(0).width, height = panels.at(0).height;
  const int total = int(panels.size()) * height + (int(panels.size()) - 1) * kSeparator;
  std::vector<uint8_t> rgba(size_t(width) * size_t(total) * 4, 48);
  for (size_t p = 0; p < panels.size(); ++p) {
    const std::vector<uint8_t> bytes = engine::toneMap(panels[p], {exposureEv});
    std::copy(bytes.begin(), bytes.end(),
              rgba.begin() + std::ptrdiff_t(p) * (height + kSeparator) * width * 4);
  }
  for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
  engine::writePng(path, width, total, rgba);
}

struct Measured {
  environment::Row row;
  std::vector<glm::dvec3> image;  // diffuse + glossy, every pixel
};

int run(const Options& o) {
  if (o.common.help) {
    std::printf("%s", usage());
    return 0;
  }
  const engine::ImageRgba32f equirect = loadEnvironment(o);
  samples::createOutputDirectory(o.outDir);
  const engine::Scene scene = environment::makeSphereRow(float(o.width) / float(o.height));

  engine::Context ctx({o.common.validation, o.common.device});
  const engine::View view = engine::cameraView(scene.cameras.at(0), o.width, o.height);
  std::printf("device: %s (%s)\nscene: %s, %u triangles, %ux%u; environment %s (%dx%d), map %u^2\n",
              ctx.info().name.c_str(), ctx.info().driver.c_str(),
              environment::sphereRowDescription().c_str(), scene.triangleCount(), o.width, o.height,
              o.environment.c_str(), equirect.width, equirect.height, o.mapSize);

  // The G-buffer and the environment's conversion, once.
  const engine::SceneGpu gpuScene = engine::uploadScene(ctx, scene);
  engine::Rasterizer rasterizer(ctx);
  engine::GBufferResolve resolve(ctx);
  engine::GBuffer gbuffer = engine::createGBuffer(ctx, o.width, o.height);
  engine::Buffer visibility(ctx, engine::Rasterizer::visibilityBytes(o.width, o.height),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  gi::EnvironmentMap map(ctx, o.mapSize);
  map.upload(ctx, equirect);
  engine::GpuProfiler profiler(ctx);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    profiler.beginFrame(cmd);
    rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, o.width, o.height});
    resolve.record(cmd, gpuScene, visibility, view, gbuffer);
    map.record(cmd);
  });
  // The conversion timed again, warm (pipelines compiled, the upload's copy done).
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    profiler.beginFrame(cmd);
    map.record(cmd, &profiler);
  });
  double conversionMs = 0.0;
  for (const engine::PassTime& p : profiler.results()) conversionMs += p.ms;
  const engine::GBufferData decoded = engine::readbackGBuffer(ctx, gbuffer);

  // The reference pixels: every stride-th sphere pixel in x and y.
  std::vector<environment::ReferencePixel> pixels;
  uint32_t spherePixels = 0;
  const auto viewDirection = [&](uint32_t x, uint32_t y) {
    return engine::cameraRayReference(view, glm::dvec2(x, y) + 0.5).dir;
  };
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      const engine::GBufferSample& s = decoded.at(x, y);
      if (s.background()) continue;
      ++spherePixels;
      if (x % o.stride || y % o.stride) continue;
      pixels.push_back(
          {{x, y},
           gi::envFisReceiverFromMaterial(s.normal, -viewDirection(x, y), s.diffuse, s.roughness,
                                          s.f0, s.f90, static_cast<gi::EnvFisBrdf>(o.brdf))});
    }
  if (pixels.empty()) throw Error("no sphere pixel to evaluate at this size and stride");
  const unsigned threads =
      o.reference.threads ? o.reference.threads : std::max(1u, std::thread::hardware_concurrency());
  std::printf(
      "reference: %zu of %u sphere pixels, %u^2 glossy and %u^2 diffuse samples each, %u "
      "threads...\n",
      pixels.size(), spherePixels, o.reference.glossyStrata, o.reference.diffuseStrata, threads);
  std::fflush(stdout);
  const std::string stem = "reference_sphere-row_" + environmentStem(o.environment) + "_" +
                           o.brdfName + "_" + std::to_string(o.width) + "x" +
                           std::to_string(o.height) + "_k" + std::to_string(o.stride);
  const environment::Reference reference =
      environment::loadOrComputeReference(o.outDir, stem, equirect, pixels, o.reference);
  std::vector<glm::dvec3> refSum, refGlossy;
  double se2 = 0.0, glossySe2 = 0.0, refMean = 0.0, refGlossyMean = 0.0;
  for (const gi::EnvReferenceShading& r : reference.shading) {
    refSum.push_back(r.value.diffuse + r.value.glossy);
    refGlossy.push_back(r.value.glossy);
    const glm::dvec3 s2 =
        r.diffuseStdError * r.diffuseStdError + r.glossyStdError * r.glossyStdError;
    se2 += s2.x + s2.y + s2.z;
    glossySe2 += glm::dot(r.glossyStdError, r.glossyStdError);
    refMean += refSum.back().x + refSum.back().y + refSum.back().z;
    refGlossyMean += r.value.glossy.x + r.value.glossy.y + r.value.glossy.z;
  }
  const double channels = 3.0 * double(pixels.size());
  const double relativeSe = std::sqrt(se2 / channels) / (refMean / channels);
  const double glossyRelativeSe = std::sqrt(glossySe2 / channels) / (refGlossyMean / channels);
  if (reference.cached)
    std::printf("reference: read %s\n", reference.file.string().c_str());
  else
    std::printf("reference: %.1f s, cached in %s\n", reference.seconds,
                reference.file.string().c_str());
  std::printf("reference: relative standard error %.5f (glossy %.5f)\n", relativeSe,
              glossyRelativeSe);

  // Every method at every count.
  gi::EnvFisShade fis(ctx);
  gi::IndirectImages out = gi::createIndirectImages(ctx, o.width, o.height);
  std::vector<Measured> measured;
  // The summed scopes of each timed frame that `body` records (warm-up frames dropped): a frame
  // records one pass alone, so the sum is that pass's time.
  const auto timeFrames = [&](const std::function<void(VkCommandBuffer)>& body) {
    std::vector<double> times;
    for (uint32_t frame = 0; frame < o.warmup + o.frames; ++frame) {
      ctx.submitAndWait([&](VkCommandBuffer cmd) {
        profiler.beginFrame(cmd);
        body(cmd);
      });
      if (frame < o.warmup) continue;
      double ms = 0.0;
      for (const engine::PassTime& p : profiler.results()) ms += p.ms;
      times.push_back(ms);
    }
    return times;
  };
  std::optional<gi::EnvSgLights> sg;
  for (const std::string& name : o.methods) {
    const Method* method = nullptr;  // null: sg
    for (const Method& m : kFisMethods)
      if (m.name == name) method = &m;
    for (uint32_t n : o.counts) {
      std::vector<double> times, setupTimes;
      gi::EnvFisShade::Inputs in;
      in.map = &map.map();
      in.sampler = map.sampler().handle();
      in.mapSize = map.size();
      in.levels = map.levels();
      in.sh = &map.sh();
      in.sampleCount = n;
      in.brdf = o.brdf;
      if (method) {
        in.mode = method->mode;
        times = timeFrames(
            [&](VkCommandBuffer cmd) { fis.record(cmd, gbuffer, view, in, out, &profiler); });
      } else {
        if (!sg) sg.emplace(ctx, map.size(), o.counts.back());
        setupTimes =
            timeFrames([&](VkCommandBuffer cmd) { sg->record(cmd, map, n, 1.0f, &profiler); });
        times =
            timeFrames([&](VkCommandBuffer cmd) { sg->shade(cmd, gbuffer, view, out, &profiler); });
      }
      Measured m;
      m.image = sumOf(out.diffuse.readbackRgba32f(ctx), out.glossy.readbackRgba32f(ctx));
      const std::vector<glm::vec4> glossy = out.glossy.readbackRgba32f(ctx);
      std::vector<glm::dvec3> testSum, testGlossy;
      for (const environment::ReferencePixel& p : pixels) {
        const size_t i = size_t{p.pixel.y} * o.width + p.pixel.x;
        testSum.push_back(m.image[i]);
        testGlossy.push_back(glm::dvec3(glossy[i]));
      }
      const engine::ErrorMetrics all = engine::compareImages(testSum, refSum);
      const engine::ErrorMetrics g = engine::compareImages(testGlossy, refGlossy);
      if (all.nonFinite || g.nonFinite)
        std::printf("warning: %s N=%u: %zu non-finite pixels left out\n", name.c_str(), n,
                    all.nonFinite);
      environment::Row& r = m.row;
      r.method = name;
      r.count = n;
      r.ms = engine::median(times);
      r.msMin = *std::min_element(times.begin(), times.end());
      r.msMax = *std::max_element(times.begin(), times.end());
      r.setupMs = engine::median(setupTimes);
      r.rmse = all.rmse;
      r.relativeRms = all.referenceMean > 0.0 ? all.rmse / all.referenceMean : 0.0;
      r.relativeMse = all.relativeMse;
      r.glossyRelativeRms = g.referenceMean > 0.0 ? g.rmse / g.referenceMean : 0.0;
      std::printf("%-15s N=%4u  %8.3f ms  rel. RMS %.4f  relMSE %.5f  glossy rel. RMS %.4f\n",
                  name.c_str(), n, r.ms, r.relativeRms, r.relativeMse, r.glossyRelativeRms);
      std::fflush(stdout);
      measured.push_back(std::move(m));
    }
  }

  // The picture: the reference, then each method at N = 40 (or the nearest count run), the
  // background showing the environment behind the spheres.
  uint32_t pictureCount = o.counts.front();
  for (uint32_t n : o.counts)
    if (std::abs(int(n) - 40) < std::abs(int(pictureCount) - 40)) pictureCount = n;
  std::vector<glm::dvec3> background(size_t{o.width} * o.height), referenceImage;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x)
      background[size_t{y} * o.width + x] =
          gi::equirectBilinear(equirect, gi::equirectFromDirection(viewDirection(x, y)));
  referenceImage = background;
  {
    // Sphere pixels take the nearest evaluated pixel (themselves at stride 1).
    std::vector<int> index(background.size(), -1);
    for (size_t i = 0; i < pixels.size(); ++i)
      index[size_t{pixels[i].pixel.y} * o.width + pixels[i].pixel.x] = int(i);
    const int k = int(o.stride);
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        if (decoded.at(x, y).background()) continue;
        int best = -1, bestDistance = 1 << 30;
        for (int dy = -k; dy <= k; ++dy)
          for (int dx = -k; dx <= k; ++dx) {
            const int px = int(x) + dx, py = int(y) + dy;
            if (px < 0 || py < 0 || px >= int(o.width) || py >= int(o.height)) continue;
            const int j = index[size_t(py) * o.width + size_t(px)];
            if (j >= 0 && dx * dx + dy * dy < bestDistance)
              best = j, bestDistance = dx * dx + dy * dy;
          }
        if (best >= 0) referenceImage[size_t{y} * o.width + x] = refSum[size_t(best)];
      }
  }
  std::vector<engine::ImageRgba32f> panels{toImage(referenceImage, o.width, o.height)};
  std::vector<std::string> order{"reference"};
  for (const Measured& m : measured) {
    if (m.row.count != pictureCount) continue;
    std::vector<glm::dvec3> image = m.image;
    for (size_t i = 0; i < image.size(); ++i)
      if (decoded.samples[i].background()) image[i] = background[i];
    panels.push_back(toImage(image, o.width, o.height));
    order.push_back(m.row.method);
  }
  // One exposure for every panel, from the reference's sphere pixels alone (the auto-exposure
  // counts only lit pixels, so the background is blacked out for it).
  std::vector<glm::dvec3> spheresOnly = referenceImage;
  for (size_t i = 0; i < spheresOnly.size(); ++i)
    if (decoded.samples[i].background()) spheresOnly[i] = glm::dvec3(0.0);
  const float ev = std::log2(engine::exposureScale(toImage(spheresOnly, o.width, o.height), {}));
  const std::string picture = "environment_n" + std::to_string(pictureCount) + ".png";

  environment::RunInfo info;
  info.device = ctx.info().name;
  info.driver = ctx.info().driver;
  info.environment = o.environment;
  info.brdf = o.brdfName;
  info.scene = environment::sphereRowDescription();
  info.width = o.width;
  info.height = o.height;
  info.mapSize = o.mapSize;
  info.frames = o.frames;
  info.warmup = o.warmup;
  info.conversionMs = conversionMs;
  info.spherePixels = spherePixels;
  info.referencePixels = uint32_t(pixels.size());
  info.stride = o.stride;
  info.glossyStrata = o.reference.glossyStrata;
  info.diffuseStrata = o.reference.diffuseStrata;
  info.referenceRelativeStdError = relativeSe;
  info.referenceGlossyRelativeStdError = glossyRelativeSe;
  info.referenceSeconds = reference.seconds;
  info.referenceThreads = threads;
  info.referenceCached = reference.cached;
  info.referenceFile = reference.file.filename().string();
  info.picture = picture;
  info.pictureCount = pictureCount;
  info.pictureOrder = order;
  std::vector<environment::Row> rows;
  for (const Measured& m : measured) rows.push_back(m.row);

  const std::filesystem::path dir(o.outDir);
  writePicture((dir / picture).string(), panels, ev);
  environment::writeReport(dir, info, rows);
  std::printf("\n%s\nwrote %s/environment.{json,csv,md} and %s (top to bottom:",
              environment::errorTable(rows).c_str(), o.outDir.c_str(), (dir / picture).c_str());
  for (const std::string& s : order) std::printf(" %s", s.c_str());
  std::printf(")\n");
  return samples::validationExitStatus(ctx, "vsgl_environment");
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_environment", [&] { return run(parseOptions(argc, argv)); });
}
