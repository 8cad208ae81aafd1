// vsgl_budget: where the indirect light's error comes from (docs/accuracy.md). For each scene
// and VSGL count, the module's image is rebuilt on the CPU with one approximation at a time
// replaced by its exact counterpart (gi/truth/error_budget.h), and every stage is scored against
// the path tracer over the whole image and per region (receivers coplanar with an emitting
// surface, near contact lines, the rest). Writes <out>/budget.md, budget.json and budget.csv,
// each stage's image and error picture, and the region map; scripts/budget_charts.sh draws the
// charts.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string_view>

#include "cli_values.h"
#include "common/rsm_view.h"
#include "default_light.h"
#include "embree_scene.h"
#include "engine/error.h"
#include "engine/image_io.h"
#include "engine/image_metrics.h"
#include "error_budget.h"
#include "gi_host.h"
#include "path_tracer.h"
#include "program_exit.h"
#include "reference_cache.h"
#include "scene_files.h"
#include "vpl_gather.h"

namespace {

using json = nlohmann::json;

struct Options {
  std::vector<std::string> scenes{"cornell", "atrium", "checker"};
  std::vector<uint32_t> counts{64, 128, 256, 512};
  uint32_t width = 128, height = 72;
  uint32_t rsm = 128;
  std::string method = "modified";
  bool planar = true;
  uint32_t ismPoints = gi::IsmSettings{}.pointsPerVsgl;
  float noise = 0.03f;
  uint32_t samples = 32;
  std::string outDir = "budget";
  samples::LightChoice light = samples::LightChoice::Auto;
  samples::CommonOptions common;
};

const char* usage() {
  return "usage: vsgl_budget [options]\n"
         "  --scenes a,b         built-in scenes or glTF files (default cornell,atrium,checker)\n"
         "  --counts 64,512      VSGL counts, 1..4096 (default 64,128,256,512)\n"
         "  --width N --height N image size, 8..1024 (default 128x72)\n" SAMPLES_LIGHT_USAGE
         "  --rsm N              RSM side, a power of two in 16..512 (default 128); the VPL\n"
         "                       stages cost pixels x texels visibility rays\n"
         "  --method NAME        modified (default), tok15, kmeans-2d or kmeans-3d\n"
         "  --planar-emitters on|off  the module's planar emitters (default on)\n"
         "  --ism-points M       ISM points per VSGL, a power of two in 64..65536 (default\n"
         "                       4096)\n"
         "  --noise R            the path tracer's relative standard error, 0.005..0.2\n"
         "                       (default 0.03, as the benchmark's references)\n"
         "  --samples N          directions per lobe and pixel of the numeric SG stage, 4..1024\n"
         "                       (default 32)\n"
         "  --out DIR            output directory (default budget; references cached in\n"
         "                       DIR/cache)\n"
         "  --device SEL         Vulkan device index or name substring\n"
         "  --validation         enable the Khronos validation layer\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (samples::Arguments args(argc, argv); args.next();) {
    const std::string_view arg = args.option();
    if (arg == "--scenes")
      o.scenes = samples::parseList(arg, args.value());
    else if (arg == "--light")
      o.light = samples::parseLightChoice(arg, args.value());
    else if (arg == "--counts")
      o.counts = samples::parseUintList(arg, args.value(), 1, 4096);
    else if (arg == "--width")
      o.width = samples::parseUint(arg, args.value(), 8, 1024);
    else if (arg == "--height")
      o.height = samples::parseUint(arg, args.value(), 8, 1024);
    else if (arg == "--rsm") {
      o.rsm = samples::parseUint(arg, args.value(), 16, 512);
      if ((o.rsm & (o.rsm - 1)) != 0)
        throw engine::Error("--rsm: " + std::to_string(o.rsm) + " is not a power of two");
    } else if (arg == "--method")
      o.method = std::string(samples::parseChoice<std::string_view>(arg, args.value(),
                                                                    {{"modified", "modified"},
                                                                     {"tok15", "tok15"},
                                                                     {"kmeans-2d", "kmeans-2d"},
                                                                     {"kmeans-3d", "kmeans-3d"}}));
    else if (arg == "--planar-emitters")
      o.planar = samples::parseChoice<bool>(arg, args.value(), {{"on", true}, {"off", false}});
    else if (arg == "--ism-points")
      o.ismPoints = samples::parseUint(arg, args.value(), 64, 65536);
    else if (arg == "--noise")
      o.noise = samples::parseFloat(arg, args.value(), 0.005f, 0.2f);
    else if (arg == "--samples")
      o.samples = samples::parseUint(arg, args.value(), 4, 1024);
    else if (arg == "--out")
      o.outDir = args.value();
    else
      samples::parseCommonOption(arg, args, o.common);
  }
  return o;
}

gi::Settings settingsFor(const Options& o, uint32_t count) {
  gi::Settings s;  // the module's defaults, as a host gets them
  s.rsmSize = o.rsm;
  s.vsglCount = count;
  s.planarEmitters = o.planar;
  s.ism.pointsPerVsgl = o.ismPoints;
  if (o.method == "tok15") s.rule = gi::KernelRule::Tok15;
  if (o.method == "kmeans-2d") s.method = gi::VsglMethod::KmeansImage;
  if (o.method == "kmeans-3d") s.method = gi::VsglMethod::KmeansWorld;
  if (const std::string problem = gi::validateSettings(s); !problem.empty())
    throw engine::Error(problem);
  return s;
}

constexpr const char* kRegionNames[] = {"background", "coplanar", "contact", "rest"};

// relMSE and mean ratio of `test` against `reference`, over the image and per region.
json score(const std::vector<glm::dvec3>& test, const std::vector<glm::dvec3>& reference,
           const std::vector<truth::BudgetRegion>& regions) {
  json out;
  for (int region = 0; region < 4; ++region) {
    std::vector<engine::PixelClass> classes(test.size(), engine::PixelClass::Excluded);
    double sumTest = 0.0, sumReference = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < test.size(); ++i)
      if (region == 0 || regions[i] == truth::BudgetRegion(region)) {
        classes[i] = engine::PixelClass::Diffuse;
        sumTest += test[i].r + test[i].g + test[i].b;
        sumReference += reference[i].r + reference[i].g + reference[i].b;
        ++count;
      }
    const engine::ErrorMetrics m = engine::compareImages(test, reference, classes);
    out[region == 0 ? "image" : kRegionNames[region]] = {
        {"pixels", count},
        {"relative_mse", count ? m.relativeMse : 0.0},
        {"mean_ratio", sumReference > 0.0 ? sumTest / sumReference : 0.0}};
  }
  return out;
}

// The region map: coplanar red, contact yellow, rest grey, background black.
void writeRegions(const std::string& png, const engine::View& view,
                  const std::vector<truth::BudgetRegion>& regions) {
  const glm::dvec3 colours[] = {{0, 0, 0}, {0.8, 0.1, 0.1}, {0.9, 0.8, 0.1}, {0.45, 0.45, 0.45}};
  std::vector<uint8_t> rgba;
  for (truth::BudgetRegion r : regions) {
    const glm::dvec3 c = colours[int(r)];
    for (int k = 0; k < 3; ++k) rgba.push_back(uint8_t(255.0 * c[k]));
    rgba.push_back(255);
  }
  engine::writePng(png, int(view.width), int(view.height), rgba);
}

std::string markdownTable(const json& row) {
  std::string md =
      "| stage | relMSE | mean ratio | coplanar: relMSE, mean | contact: relMSE, mean | rest: "
      "relMSE, mean |\n|---|---|---|---|---|---|\n";
  char line[512];
  for (const json& stage : row["stages"]) {
    const json& s = stage["score"];
    auto pair = [&](const char* region) {
      if (s[region]["pixels"].get<size_t>() == 0) return std::string("—");  // no such pixels
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.4f, %.3f", s[region]["relative_mse"].get<double>(),
                    s[region]["mean_ratio"].get<double>());
      return std::string(cell);
    };
    std::snprintf(line, sizeof line, "| %s | %.4f | %.3f | %s | %s | %s |\n",
                  stage["name"].get<std::string>().c_str(),
                  s["image"]["relative_mse"].get<double>(), s["image"]["mean_ratio"].get<double>(),
                  pair("coplanar").c_str(), pair("contact").c_str(), pair("rest").c_str());
    md += line;
  }
  return md;
}

int run(const Options& o) {
  if (o.common.help) {
    std::printf("%s", usage());
    return 0;
  }
  for (uint32_t n : o.counts) settingsFor(o, n);  // bad settings fail before any work
  std::vector<engine::Scene> scenes;
  for (const std::string& name : o.scenes) {
    scenes.push_back(samples::loadScene(name));
    const std::string note =
        samples::applyLightChoice(scenes.back(), o.light, false, float(o.width) / float(o.height));
    if (!note.empty()) std::printf("%s\n", note.c_str());
    samples::bouncingLights(scenes.back());  // throws for none or too many
  }
  const std::filesystem::path out(o.outDir);
  samples::createOutputDirectory(o.outDir);
  const truth::ReferenceCache cache((out / "cache").string());
  engine::Context ctx({o.common.validation, o.common.device});

  json rows = json::array();
  std::string md = "# Error budget\n\n";
  for (size_t si = 0; si < scenes.size(); ++si) {
    const engine::Scene& scene = scenes[si];
    const std::string name = std::filesystem::path(o.scenes[si]).stem().string();
    const engine::View view = samples::sceneView(scene, o.width, o.height);
    // Every light of the scene bounces, its views numbered in order as the module's
    // FrameOutput::vsglViews and rsmVpls number them (a point light has six).
    const std::vector<uint32_t> lights = samples::bouncingLights(scene);
    size_t viewCount = 0;
    for (uint32_t l : lights)
      viewCount += gi::makeRsmViews(scene.bounds(), scene.lights[l], o.rsm).size();
    truth::PathTraceSettings trace;
    trace.relativeError = o.noise;
    trace.progress = true;
    const truth::PathTraceImage traced = truth::cachedPathTrace(cache, scene, view, lights, trace);
    std::vector<glm::dvec3> reference(traced.diffuse.size());
    for (size_t i = 0; i < reference.size(); ++i)
      reference[i] = traced.diffuse[i] + traced.glossy[i];

    const truth::EmbreeScene rays(scene);
    const std::vector<truth::Vpl> vpls = truth::rsmVpls(scene, rays, lights, o.rsm);
    const truth::VplGatherImage gathered = truth::vplGather(scene, rays, view, vpls);
    std::vector<glm::dvec3> rsmStage(reference.size());
    for (size_t i = 0; i < rsmStage.size(); ++i)
      rsmStage[i] = gathered.diffuse[i] + gathered.glossy[i];
    const std::vector<truth::BudgetRegion> regions = truth::budgetRegions(scene, rays, view, vpls);
    writeRegions((out / (name + "_regions.png")).string(), view, regions);
    std::printf("%s: reference %.1f s, %zu VPLs gathered in %.1f s\n", name.c_str(), traced.seconds,
                vpls.size(), gathered.seconds);

    const engine::SceneGpu gpuScene = engine::uploadScene(ctx, scene);
    engine::GBuffer gbuffer = samples::renderGBuffer(ctx, gpuScene, view);
    md += "## " + name + "\n\n";
    for (uint32_t count : o.counts) {
      const gi::Settings settings = settingsFor(o, count);
      std::unique_ptr<gi::IndirectLighting> lighting =
          samples::createIndirect(ctx, settings, o.width, o.height, gpuScene, scene);
      gi::FrameOutput output;
      const gi::FrameInput in = samples::frameInput(gbuffer, view, scene.lights);
      ctx.submitAndWait(
          [&](VkCommandBuffer cmd) { samples::check(lighting->record(cmd, in, &output)); });
      for (engine::Image* image :
           {&gbuffer.depth, &gbuffer.normal, &gbuffer.diffuse, &gbuffer.specular})
        image->setLayout(output.gbufferLayout);
      const std::vector<glm::dvec3> module =
          samples::indirectSum(samples::readIndirect(ctx, output, o.width, o.height));
      const std::vector<gpu::Vsgl> vsgls = samples::readVsgls(ctx, output);
      if (output.viewCount != viewCount)
        throw engine::Error(name + ": the module bounced " + std::to_string(output.viewCount) +
                            " RSM views of the scene's " + std::to_string(viewCount) +
                            " (a light without power gets none); the budget needs them all");
      truth::KernelLayout layout{o.rsm, std::vector<uint32_t>(vsgls.size(), 0)};
      const std::vector<glm::uvec2> ranges = samples::readVsglViews(ctx, output);
      for (uint32_t v = 0; v < ranges.size(); ++v)
        for (uint32_t k = ranges[v].x; k < ranges[v].x + ranges[v].y && k < vsgls.size(); ++k)
          layout.views[k] = v;

      const std::vector<double> weights = truth::kernelTexelWeights(vsgls, layout, vpls);
      double covered = 0.0, power = 0.0;  // the VSGLs' share of the RSM's power
      for (const truth::Vpl& v : vpls) {
        const double p = v.incident.r + v.incident.g + v.incident.b;
        covered += weights[v.texel] * p;
        power += p;
      }
      const std::vector<truth::Vpl> weighted = truth::weightedVpls(vpls, weights);
      const truth::VplGatherImage grouped = truth::vplGather(scene, rays, view, weighted);
      const truth::VplGatherImage groupedUnshadowed =
          truth::vplGather(scene, rays, view, weighted, 0, false);
      std::vector<glm::dvec3> groupingStage(reference.size()), groupingUnshadowed(reference.size());
      for (size_t i = 0; i < groupingStage.size(); ++i) {
        groupingStage[i] = grouped.diffuse[i] + grouped.glossy[i];
        groupingUnshadowed[i] = groupedUnshadowed.diffuse[i] + groupedUnshadowed.glossy[i];
      }
      truth::VsglStageSettings stageSettings;
      stageSettings.planarEmitters = settings.planarEmitters;
      stageSettings.glossy = settings.glossy;
      stageSettings.ismCentreOffset = settings.ism.centreOffset;
      stageSettings.samplesPerLobe = o.samples;
      stageSettings.kernelVpls = &vpls;
      stageSettings.kernels = layout;
      const truth::VsglStageImages sg = truth::vsglStages(scene, rays, view, vsgls, stageSettings);

      // Which VSGLs the light model's error comes from: the flat ones' light, then the others',
      // replaced by their own VPLs (unshadowed). The weights are linear in the VSGLs, so the
      // others' VPL image is the whole one less the flat ones'. k-means clusters map to no
      // texels by their record, so their split is not made.
      std::vector<gpu::Vsgl> flat;
      truth::KernelLayout flatLayout{o.rsm, {}};
      double flatPower = 0.0, allPower = 0.0;
      bool kernels = true;
      for (size_t k = 0; k < vsgls.size(); ++k) {
        const gpu::Vsgl& v = vsgls[k];
        const double p = double(v.diffuse.power.a) + double(v.specular.power.a);
        allPower += p;
        kernels = kernels && v.kernel.z >= 0.0f;
        if (!truth::flatVsgl(v)) continue;
        flat.push_back(v);
        flatLayout.views.push_back(layout.views[k]);
        flatPower += p;
      }
      std::vector<glm::dvec3> flatExact, nonFlatExact;
      if (kernels) {
        const truth::VplGatherImage flatGroup = truth::vplGather(
            scene, rays, view,
            truth::weightedVpls(vpls, truth::kernelTexelWeights(flat, flatLayout, vpls)), 0, false);
        for (size_t i = 0; i < reference.size(); ++i) {
          const glm::dvec3 flatVpls = flatGroup.diffuse[i] + flatGroup.glossy[i];
          flatExact.push_back(flatVpls + sg.unshadowed[i] - sg.unshadowedFlat[i]);
          nonFlatExact.push_back(sg.unshadowedFlat[i] + groupingUnshadowed[i] - flatVpls);
        }
      }

      std::vector<std::pair<const char*, const std::vector<glm::dvec3>*>> stages = {
          {"rsm", &rsmStage},
          {"grouping", &groupingStage},
          {"grouping-unshadowed", &groupingUnshadowed},
          {"sg-model-unshadowed", &sg.unshadowed}};
      if (kernels) {
        stages.push_back({"sg-unshadowed-flat-exact", &flatExact});
        stages.push_back({"sg-unshadowed-nonflat-exact", &nonFlatExact});
      }
      stages.insert(stages.end(), {{"sg-model-area-visibility", &sg.areaVisible},
                                   {"sg-model", &sg.numeric},
                                   {"analytic", &sg.analytic},
                                   {"module", &module}});
      json row = {{"scene", name},
                  {"count", count},
                  {"method", o.method},
                  {"planar_emitters", o.planar},
                  {"ism_points_per_vsgl", o.ismPoints},
                  {"width", o.width},
                  {"height", o.height},
                  {"rsm", o.rsm},
                  {"reference_noise", o.noise},
                  {"kernel_power_share", power > 0.0 ? covered / power : 0.0},
                  {"flat_vsgls", flat.size()},
                  {"flat_power_share", allPower > 0.0 ? flatPower / allPower : 0.0},
                  {"stages", json::array()}};
      for (const auto& [stage, image] : stages) {
        row["stages"].push_back({{"name", stage}, {"score", score(*image, reference, regions)}});
        const std::string base =
            (out / (name + "_" + std::to_string(count) + "_" + stage)).string();
        engine::writeExr(base + ".exr", samples::imageFrom(o.width, o.height,
                                                           [&](size_t i) { return (*image)[i]; }));
        engine::writeFalseColourError(base + "_error.png", int(o.width), int(o.height), *image,
                                      reference,
                                      engine::percentileAbsError(rsmStage, reference, 0.99) * 4.0);
      }
      std::printf(
          "%s N = %u (kernels carry %.4f of the RSM's power; %zu flat VSGLs carry %.4f "
          "of theirs; CPU stages %.1f s):\n%s\n",
          name.c_str(), count, row["kernel_power_share"].get<double>(), flat.size(),
          row["flat_power_share"].get<double>(),
          grouped.seconds + groupedUnshadowed.seconds + sg.seconds, markdownTable(row).c_str());
      std::fflush(stdout);
      char heading[200];
      std::snprintf(heading, sizeof heading,
                    "### N = %u\n\nThe kernels carry %.4f of the RSM's power; %zu flat VSGLs carry "
                    "%.4f of the VSGLs' power.\n\n",
                    count, row["kernel_power_share"].get<double>(), flat.size(),
                    row["flat_power_share"].get<double>());
      md += heading + markdownTable(row) + "\n";
      rows.push_back(row);
    }
  }
  // Written whole at the end (renamed into place), so an interrupted run leaves no half table.
  std::string csv = "scene,count,stage,relative_mse,mean_ratio\n";
  for (const json& row : rows)
    for (const json& stage : row["stages"])
      csv += row["scene"].get<std::string>() + "," + std::to_string(row["count"].get<uint32_t>()) +
             "," + stage["name"].get<std::string>() + "," +
             std::to_string(stage["score"]["image"]["relative_mse"].get<double>()) + "," +
             std::to_string(stage["score"]["image"]["mean_ratio"].get<double>()) + "\n";
  for (const auto& [file, text] :
       {std::pair{std::string("budget.json"), rows.dump(2) + "\n"},
        std::pair{std::string("budget.md"), md}, std::pair{std::string("budget.csv"), csv}}) {
    const std::filesystem::path path = out / file, partial = out / (file + ".partial");
    std::ofstream(partial) << text;
    std::filesystem::rename(partial, path);
  }
  std::printf("wrote %s/budget.{md,json,csv}, the stages' images and error pictures, the regions\n",
              o.outDir.c_str());
  return samples::validationExitStatus(ctx, "vsgl_budget");
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_budget", [&] { return run(parseOptions(argc, argv)); });
}
