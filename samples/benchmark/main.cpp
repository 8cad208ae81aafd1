// vsgl_benchmark: what accuracy costs in time. For every scene x method x VSGL count x K of a
// preset it renders frames through the public API (as vsgl_render does), times every pass
// (median, 5th and 95th percentile over the measured frames), scores the indirect light against
// the path-traced reference (gi/truth, cached), and writes one JSON record per row plus
// benchmark.json and benchmark.csv. Each finished row is stored at once under <out>/rows, so an
// interrupted run resumes where it stopped. docs/benchmarks.md explains the output.
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>
#include <utility>

#include "cli_values.h"
#include "default_light.h"
#include "engine/gbuffer.h"
#include "engine/image_metrics.h"
#include "engine/machine_peak.h"
#include "engine/rasterizer.h"
#include "gi_host.h"
#include "path_tracer.h"
#include "presets.h"
#include "program_exit.h"
#include "reference_cache.h"
#include "report.h"
#include "scene_files.h"
#include "vpl_gather.h"

namespace {

using nlohmann::json;

struct Options {
  std::string preset = "ci";
  std::string outDir = "bench";
  samples::CommonOptions common;  // --device, --validation, --help
  // Overrides of the preset's sweep (empty / 0: the preset's own).
  std::vector<std::string> scenes;
  std::vector<std::string> methods;
  std::vector<uint32_t> counts;
  uint32_t width = 0, height = 0;
  samples::LightChoice light = samples::LightChoice::Auto;
  std::string lightName = "auto";  // as typed: part of every row's identity
  std::string camera;              // --camera; "" = each scene's first (then not in the identity)
};

const char* usage() {
  return "usage: vsgl_benchmark [options]\n"
         "  --preset NAME   ci (seconds; the test suite's smoke run), default or paper\n"
         "  --out DIR       output directory (default bench): benchmark.json, benchmark.csv,\n"
         "                  rows/ (one record per finished row: a rerun resumes) and cache/\n"
         "                  (path-traced references)\n"
         "  --scenes LIST   comma-separated scenes (built-in names or .gltf/.glb files) instead\n"
         "                  of the preset's\n"
         "  --methods LIST  comma-separated methods instead of the preset's: tok15, modified,\n"
         "                  modified-full, modified-culled, modified-full-culled,\n"
         "                  modified-sg-emitter, modified-full-sg-emitter, kmeans-2d, kmeans-3d,\n"
         "                  vpl (the GPU VPL baseline)\n"
         "  --counts LIST   comma-separated VSGL counts, 1..32768, instead of the preset's\n"
         "  --width N --height N  image size, 1..8192, instead of the preset's (the path-traced\n"
         "                  reference's cost grows with the pixel count)\n" SAMPLES_LIGHT_USAGE
             SAMPLES_CAMERA_USAGE
         "  --device SEL    Vulkan device index or name substring\n"
         "  --validation    enable the Khronos validation layer\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (samples::Arguments args(argc, argv); args.next();) {
    const std::string_view arg = args.option();
    if (arg == "--preset")
      o.preset = args.value();
    else if (arg == "--out")
      o.outDir = args.value();
    else if (arg == "--scenes")
      o.scenes = samples::parseList(arg, args.value());
    else if (arg == "--camera")
      o.camera = args.value();
    else if (arg == "--light") {
      o.lightName = args.value();
      o.light = samples::parseLightChoice(arg, o.lightName);
    } else if (arg == "--methods") {
      o.methods = samples::parseList(arg, args.value());
      for (const std::string& m : o.methods)
        if (std::find(bench::methods().begin(), bench::methods().end(), m) ==
            bench::methods().end())
          throw engine::Error("--methods: '" + m +
                              "' is not one of tok15, modified, modified-full, modified-culled, "
                              "modified-full-culled, modified-sg-emitter, "
                              "modified-full-sg-emitter, kmeans-2d, kmeans-3d, vpl");
    } else if (arg == "--counts")
      o.counts = samples::parseUintList(arg, args.value(), 1, gi::kMaxVsglCount);
    else if (arg == "--width")
      o.width = samples::parseUint(arg, args.value(), 1, 8192);
    else if (arg == "--height")
      o.height = samples::parseUint(arg, args.value(), 1, 8192);
    else
      samples::parseCommonOption(arg, args, o.common);
  }
  if (o.outDir.empty()) throw engine::Error("--out: empty path");
  return o;
}

// The q-quantile (0..1) of `values` by linear interpolation between order statistics.
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double x = q * double(values.size() - 1);
  const auto i = static_cast<size_t>(x);
  const size_t j = std::min(i + 1, values.size() - 1);
  return values[i] + (x - double(i)) * (values[j] - values[i]);
}

gi::Settings settingsFor(const bench::Preset& p, const std::string& method, uint32_t count,
                         float k) {
  gi::Settings s;
  s.rsmSize = p.rsmSize;
  s.vsglCount = count;
  s.kernelScale = k;
  s.brsm.importanceCount = p.importanceCount;
  s.brsm.gridSize = std::min(s.brsm.gridSize, p.rsmSize);
  if (method == "tok15") s.rule = gi::KernelRule::Tok15;
  // The module's method with every pixel shaded: what adaptive shading saves, and costs.
  if (method == "modified-full" || method == "modified-full-culled" ||
      method == "modified-full-sg-emitter")
    s.adaptive.enabled = false;
  // Planar emitters off: what they cost per pixel-VSGL pair, and what they buy.
  if (method == "modified-sg-emitter" || method == "modified-full-sg-emitter")
    s.planarEmitters = false;
  // VSGL culling on: what it saves, and the light it loses.
  if (method == "modified-culled" || method == "modified-full-culled") s.culling.enabled = true;
  if (method == "kmeans-2d") s.method = gi::VsglMethod::KmeansImage;
  if (method == "kmeans-3d") s.method = gi::VsglMethod::KmeansWorld;
  if (method == "vpl") s.method = gi::VsglMethod::Vpl;
  if (std::string bad = gi::validateSettings(s); !bad.empty()) throw engine::Error(bad);
  return s;
}

// Whether two rows' settings make the same VSGLs (they may shade them differently).
bool sameVsgls(const gi::Settings& a, const gi::Settings& b) {
  return a.method == b.method && a.rule == b.rule && a.vsglCount == b.vsglCount &&
         a.kernelScale == b.kernelScale;
}

// FNV-1a of a row's identity: its file name under rows/.
std::string rowKey(const json& identity) {
  uint64_t h = 1469598103934665603ull;
  for (char c : identity.dump()) h = (h ^ uint8_t(c)) * 1099511628211ull;
  char name[17];
  std::snprintf(name, sizeof(name), "%016llx", static_cast<unsigned long long>(h));
  return name;
}

double peakResidentMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

// One scene's fixed inputs: its G-buffer (rendered once) and the path-traced reference.
struct SceneRun {
  engine::Scene scene;
  engine::View view;
  std::vector<uint32_t> lights;  // the bouncing lights' indices in scene.lights: every one
  std::unique_ptr<engine::SceneGpu> gpuScene;
  std::unique_ptr<engine::GBuffer> gbuffer;
  std::vector<glm::dvec3> reference;  // path-traced indirect light
};

// `scene` (loaded and checked for its bouncing lights before anything ran) on the device.
SceneRun prepareScene(engine::Context& ctx, const bench::Preset& p, const std::string& name,
                      engine::Scene scene, const truth::ReferenceCache& cache) {
  SceneRun r;
  r.scene = std::move(scene);
  r.view = samples::sceneView(r.scene, p.width, p.height);
  r.lights = samples::bouncingLights(r.scene);
  r.gpuScene = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx, r.scene));
  r.gbuffer = std::make_unique<engine::GBuffer>(samples::renderGBuffer(ctx, *r.gpuScene, r.view));
  truth::PathTraceSettings trace;
  trace.relativeError = p.referenceNoise;
  trace.progress = true;
  bool fromCache = false;
  const truth::PathTraceImage image =
      truth::cachedPathTrace(cache, r.scene, r.view, r.lights, trace, &fromCache);
  std::printf("%s: reference %s (%.1f s to trace)\n", name.c_str(),
              fromCache ? "from the cache" : "traced", image.seconds);
  r.reference.resize(image.diffuse.size());
  for (size_t i = 0; i < r.reference.size(); ++i)
    r.reference[i] = image.diffuse[i] + image.glossy[i];
  return r;
}

json errorRecord(const std::vector<glm::dvec3>& image, const std::vector<glm::dvec3>& reference,
                 const bench::Preset& p) {
  const engine::ErrorMetrics e = engine::compareImages(image, reference);
  return {{"rmse", e.rmse},
          {"rmse_of_mean", e.referenceMean > 0.0 ? e.rmse / e.referenceMean : 0.0},
          {"relative_mse", e.relativeMse},
          {"psnr_db", e.psnr},
          {"non_finite_pixels", e.nonFinite},
          {"reference",
           "path tracer, " + std::to_string(p.referenceNoise) + " relative standard error"}};
}

// One frame series of a row: every pass's times over the measured frames, in first-seen order.
struct PassSamples {
  std::map<std::string, std::vector<double>> times;
  std::map<std::string, uint32_t> dispatches;
  std::vector<std::string> order;
};

// Rows of one scene and VSGL count, measured together: their frames interleave, one frame of
// each in turn. On a shared machine, medians drift by tens of percent over minutes; interleaved
// rows see the same drift, so the ratios between them hold.
std::vector<json> runRows(engine::Context& ctx, const bench::Preset& p, SceneRun& s,
                          const std::vector<gi::Settings>& settings) {
  const gi::FrameInput input = samples::frameInput(*s.gbuffer, s.view, s.scene.lights);
  std::vector<std::unique_ptr<gi::IndirectLighting>> lightings;
  for (const gi::Settings& one : settings)
    lightings.push_back(samples::createIndirect(ctx, one, p.width, p.height, *s.gpuScene, s.scene));
  std::vector<gi::FrameOutput> outputs(settings.size());
  std::vector<PassSamples> samples(settings.size());
  for (uint32_t frame = 0; frame < p.warmup + p.frames; ++frame)
    for (size_t i = 0; i < lightings.size(); ++i) {
      ctx.submitAndWait([&](VkCommandBuffer cmd) {
        samples::check(lightings[i]->record(cmd, input, &outputs[i]));
      });
      if (frame < p.warmup) continue;  // the first frame compiles the pipelines
      for (const gi::PassTime& t : lightings[i]->lastFrameTimes()) {
        if (!samples[i].times.count(t.name)) samples[i].order.push_back(t.name);
        samples[i].times[t.name].push_back(t.ms);
        samples[i].dispatches[t.name] = t.dispatches;
      }
    }
  std::vector<json> rows;
  std::vector<std::vector<glm::dvec3>> images;
  for (size_t i = 0; i < lightings.size(); ++i) {
    PassSamples& m = samples[i];
    json passes = json::array();
    for (const std::string& name : m.order)
      passes.push_back({{"name", name},
                        {"median_ms", quantile(m.times[name], 0.5)},
                        {"p5_ms", quantile(m.times[name], 0.05)},
                        {"p95_ms", quantile(m.times[name], 0.95)},
                        {"dispatches", m.dispatches[name]}});
    images.push_back(
        samples::indirectSum(samples::readIndirect(ctx, outputs[i], p.width, p.height)));
    const gi::ShadingCounts c = lightings[i]->lastShadingCounts();
    rows.push_back({{"passes", passes},
                    {"error", errorRecord(images.back(), s.reference, p)},
                    {"plan", lightings[i]->lastPlan().reasons},
                    {"shading_counts",
                     {{"adaptive", c.adaptive},
                      {"shaded", c.shaded},
                      {"interpolated", c.interpolated},
                      {"reused", c.reused},
                      {"pixels_from", c.pixelsFrom},
                      {"sky_pixels", c.skyPixels},
                      {"vsgl_tests", c.vsglTests},
                      {"vsgls_skipped", c.vsglsSkipped}}},
                    {"peak_resident_mb", peakResidentMegabytes()}});
  }
  // Adaptive rows against the row of the same frame shaded at every pixel, and culled rows
  // against the same shading without culling, when they are here.
  for (size_t i = 0; i < settings.size(); ++i)
    for (size_t j = 0; j < settings.size(); ++j) {
      if (!sameVsgls(settings[i], settings[j])) continue;
      const gi::Settings &a = settings[i], &b = settings[j];
      if (a.adaptive.enabled && !b.adaptive.enabled && a.culling.enabled == b.culling.enabled)
        rows[i]["error_against_full_shading"] =
            engine::compareImages(images[i], images[j]).relativeMse;
      if (a.culling.enabled && !b.culling.enabled && a.adaptive.enabled == b.adaptive.enabled)
        rows[i]["error_against_unculled"] = engine::compareImages(images[i], images[j]).relativeMse;
    }
  return rows;
}

// The brute-force VPL gather over an rsm^2 RSM (gi/truth/vpl_gather.h) as a row: its CPU wall
// time stands in for the frame, so the charts place what VSGLs approximate beside them.
json runVplRow(const bench::Preset& p, SceneRun& s, uint32_t rsm) {
  const truth::EmbreeScene rays(s.scene);
  const std::vector<truth::Vpl> vpls = truth::rsmVpls(s.scene, rays, s.lights, rsm);
  const truth::VplGatherImage g = truth::vplGather(s.scene, rays, s.view, vpls);
  std::vector<glm::dvec3> image(g.diffuse.size());
  for (size_t i = 0; i < image.size(); ++i) image[i] = g.diffuse[i] + g.glossy[i];
  const double ms = 1e3 * g.seconds;
  json passes = json::array();
  for (const char* name : {"frame", "vpl gather (CPU)"})
    passes.push_back(
        {{"name", name}, {"median_ms", ms}, {"p5_ms", ms}, {"p95_ms", ms}, {"dispatches", 0}});
  return {{"passes", passes},
          {"error", errorRecord(image, s.reference, p)},
          {"vpl_count", g.vplCount},
          {"peak_resident_mb", peakResidentMegabytes()}};
}

int run(const Options& o) {
  if (o.common.help) {
    std::printf("%s", usage());
    return 0;
  }
  bench::Preset p = bench::preset(o.preset);
  if (!o.scenes.empty()) p.scenes = o.scenes;
  if (!o.methods.empty()) p.methods = o.methods;
  if (!o.counts.empty()) p.counts = o.counts;
  if (o.width) p.width = o.width;
  if (o.height) p.height = o.height;
  // The rows of one scene in groups measured together (runRows): per VSGL count, every method
  // (and K, for the filtered ones); then the VPL gather at each of its RSM sizes (count = RSM
  // side, k = 0), one group each.
  struct RowSpec {
    std::string method;
    uint32_t count;
    float k;
  };
  std::vector<std::vector<RowSpec>> groups;
  for (uint32_t count : p.counts) {
    groups.emplace_back();
    for (const std::string& method : p.methods)
      for (float k : p.kernelScales)
        if (bench::hasKernelScale(method) || k == p.kernelScales.front())
          groups.back().push_back({method, count, k});
  }
  for (uint32_t rsm : p.vplRsmSizes) groups.push_back({{"vpl-gather", rsm, 0.0f}});
  size_t total = 0;
  for (const auto& group : groups)
    for (const RowSpec& spec : group) {  // a bad override fails before anything is measured
      if (spec.method != "vpl-gather") settingsFor(p, spec.method, spec.count, spec.k);
      ++total;
    }
  total *= p.scenes.size();
  std::vector<engine::Scene> scenes;  // loaded once, checked before anything is measured
  for (const std::string& name : p.scenes) {
    scenes.push_back(samples::loadScene(name));
    samples::selectCamera(scenes.back(), o.camera);
    const std::string note =
        samples::applyLightChoice(scenes.back(), o.light, false, float(p.width) / float(p.height));
    if (!note.empty()) std::printf("%s\n", note.c_str());
    samples::bouncingLights(scenes.back());  // throws for none or too many
  }
  const std::filesystem::path out(o.outDir);
  auto rowFile = [&](const json& identity) { return out / "rows" / (rowKey(identity) + ".json"); };
  samples::createOutputDirectory(o.outDir);
  samples::createOutputDirectory((out / "rows").string());
  const truth::ReferenceCache cache((out / "cache").string());

  engine::Context ctx({o.common.validation, o.common.device});
  const json machine = {{"device", ctx.info().name},
                        {"driver", ctx.info().driver},
                        {"revision", VSGL_REVISION},
                        {"fma_peak_gflops", engine::measureFmaPeak(ctx).gflops},
                        {"copy_bandwidth_gbs", engine::measureBandwidthPeak(ctx).gbPerSecond}};
  std::printf("device: %s (%s), revision %s; FMA peak %.1f GFLOP/s, copy bandwidth %.1f GB/s\n",
              ctx.info().name.c_str(), ctx.info().driver.c_str(), VSGL_REVISION,
              machine["fma_peak_gflops"].get<double>(),
              machine["copy_bandwidth_gbs"].get<double>());

  json rows = json::array();
  size_t done = 0;
  for (size_t sceneIndex = 0; sceneIndex < p.scenes.size(); ++sceneIndex) {
    const std::string& sceneName = p.scenes[sceneIndex];
    std::optional<SceneRun> scene;  // prepared at its first row that is not cached
    for (const std::vector<RowSpec>& group : groups) {
      std::vector<json> identities, records(group.size());
      std::vector<size_t> pending;
      for (size_t i = 0; i < group.size(); ++i) {
        const RowSpec& spec = group[i];
        identities.push_back({{"preset", p.name},
                              {"scene", sceneName},
                              {"light", o.lightName},
                              {"method", spec.method},
                              {"count", spec.count},
                              {"k", spec.k},
                              {"width", p.width},
                              {"height", p.height},
                              {"rsm", spec.method == "vpl-gather" ? spec.count : p.rsmSize},
                              {"frames", p.frames},
                              {"warmup", p.warmup},
                              {"reference_noise", p.referenceNoise},
                              {"device", ctx.info().name},
                              {"revision", VSGL_REVISION}});
        if (!o.camera.empty()) identities.back()["camera"] = o.camera;
        if (std::ifstream in(rowFile(identities[i])); in)
          records[i] = json::parse(in, nullptr, false);
        if (records[i].is_discarded() || !records[i].is_object() ||
            records[i].value("identity", json()) != identities[i])
          pending.push_back(i);
      }
      if (!pending.empty()) {
        if (!scene) scene = prepareScene(ctx, p, sceneName, scenes[sceneIndex], cache);
        std::vector<json> measured;
        if (group.front().method == "vpl-gather") {
          measured.push_back(runVplRow(p, *scene, group.front().count));
        } else {
          std::vector<gi::Settings> settings;
          for (size_t i : pending)
            settings.push_back(settingsFor(p, group[i].method, group[i].count, group[i].k));
          measured = runRows(ctx, p, *scene, settings);
        }
        for (size_t j = 0; j < pending.size(); ++j) {
          json& row = records[pending[j]];
          row = measured[j];
          row["identity"] = identities[pending[j]];
          // A row file is complete or absent.
          bench::writeFile(rowFile(identities[pending[j]]), row.dump(2) + "\n");
        }
      }
      for (size_t i = 0; i < group.size(); ++i) {
        json flat = identities[i];
        for (auto& [key, value] : records[i].items())
          if (key != "identity") flat[key] = value;
        std::printf(
            "[%zu/%zu] %s %s N=%u K=%g: frame %.1f ms, generation %.2f ms, RMSE %.1f %% of "
            "mean\n",
            ++done, total, sceneName.c_str(), group[i].method.c_str(), group[i].count,
            double(group[i].k), bench::passMedian(flat, "frame"), bench::generationMs(flat),
            100.0 * flat["error"]["rmse_of_mean"].get<double>());
        std::fflush(stdout);
        rows.push_back(flat);
      }
    }
  }
  // The tables read best method by method: per scene, rows in the preset's method order (the
  // VPL gather last), then by count and K.
  auto rank = [&](const json& r) {
    auto index = [](const std::vector<std::string>& list, const std::string& name) {
      return size_t(std::find(list.begin(), list.end(), name) - list.begin());
    };
    return std::make_tuple(index(p.scenes, r["scene"]), index(p.methods, r["method"]),
                           r["count"].get<uint32_t>(), r["k"].get<double>());
  };
  std::stable_sort(rows.begin(), rows.end(),
                   [&](const json& a, const json& b) { return rank(a) < rank(b); });
  bench::writeReport(out, machine, rows);
  std::printf(
      "wrote %s, benchmark.csv and benchmark_passes.csv (charts: scripts/bench_charts.sh %s)\n",
      (out / "benchmark.json").c_str(), o.outDir.c_str());
  return samples::validationExitStatus(ctx, "vsgl_benchmark");
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_benchmark", [&] { return run(parseOptions(argc, argv)); });
}
