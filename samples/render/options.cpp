#include "options.h"

#include <algorithm>
#include <string_view>
#include <tuple>
#include <utility>

#include "cli_values.h"
#include "engine/error.h"
#include "scene_files.h"
#include "settings_fields.h"

namespace render {

using samples::parseChoice;
using samples::parseFloat;
using samples::parseUint;
const char* usage() {
  return "usage: vsgl_render [options]\n"
         "  --scene NAME|FILE    built-in scene (cornell, atrium, checker, lounge) or .gltf/.glb "
         "(default "
         "cornell);\n"
         "                       sphere-room:N and sphere-room-outside:N add N sphere triangles\n"
         "                       to a matte Cornell box (engine/builtin_scenes.h)\n"
         "  --out DIR            output directory (default out)\n"
         "  --width N --height N image size in pixels, 1..8192 (default 640x360)\n"
         "  --frames N           measured frames, 1..1000 (default 3)\n"
         "  --warmup N           unmeasured frames before them, 0..100 (default 1; the first\n"
         "                       frame also pays for compiling the pipelines)\n"
         "  --motion NAME        what moves over the frames, as in vsgl_flicker: static "
         "(default),\n"
         "                       orbit (the camera), sweep (the first spot or directional light)\n"
         "                       or move (a box slides across the floor)\n"
         "  --reuse on|off       reuse across frames: a pass reruns only when its inputs changed\n"
         "                       (default on; docs/techniques/reuse.md)\n"
         "  --shadow-res N       shadow-map texels per side, 16..4096 (default: from the image "
         "size)\n"
         "  --no-shadows         direct light without shadow maps\n"
         "  --shadows own|module  the host's own shadow maps (default), or the module's light\n"
         "                       views where it bounces the light, at the RSM's size\n"
         "                       (docs/integration.md, \"The light's view\")\n"
         "  --exposure EV        fixed exposure in stops for the PNG (default: auto)\n"
         "  --device SEL         Vulkan device index or name substring (default: VSGL_DEVICE or "
         "auto)\n"
         "  --list-devices       print the Vulkan devices and exit\n"
         "  --validation         enable the Khronos validation layer\n"
         "  --export-gltf PATH   also write the scene as a .gltf file\n" SAMPLES_LIGHT_USAGE
             SAMPLES_CAMERA_USAGE
         "indirect light (VSGLs through the public API, gi/include/gi/settings.h):\n"
         "  --settings FILE      gi::Settings as 'key = value' lines (samples/common/\n"
         "                       settings_fields.h), read over the values given so far; options\n"
         "                       after it override it\n"
         "  --no-indirect        direct light only\n"
         "  --method NAME        modified (modified FIS, default), tok15 (Tokuyoshi 2015's kernel\n"
         "                       rule), or the baselines kmeans-2d / kmeans-3d (k-means of the\n"
         "                       RSM's texels in image or world space) and vpl (instant\n"
         "                       radiosity: --count point lights from the same PDF)\n"
         "  --kmeans-iterations N  k-means iterations per frame, 1..64 (default 4)\n"
         "  --kmeans-weights W   pdf (default) or uniform texel weights in the k-means centres\n"
         "  --kmeans-fresh       seed k-means afresh each frame (default: previous centres)\n"
         "  --pdf NAME           brsm (view-dependent, default) or flux\n"
         "  --count N            VSGLs per frame, 1..32768 (default 128; the paper: 1024)\n"
         "  --k K                kernel mass K/N, 1..N (default 1)\n"
         "  --rsm N              RSM side, a power of two in 16..2048 (default 256)\n"
         "  --ism on|off         imperfect-shadow-map visibility (default on)\n"
         "  --ism-size N         ISM side per VSGL, a power of two in 16..256 (default 64)\n"
         "  --no-glossy          skip the glossy (GGX) indirect term\n"
         "  --planner on|off     the effect planner's decisions (default on; docs/integration.md)\n"
         "  --adaptive on|off    adaptive shading: coarse to fine, interpolated where the surface\n"
         "                       and the light agree (default on; "
         "docs/techniques/adaptive-shading.md)\n"
         "  --adaptive-level L   its coarsest level, 0..3: one shaded pixel in 2^L x 2^L (default "
         "2)\n"
         "  --adaptive-tolerance T  light spread allowed for interpolation, 0..10 (default 0.2)\n"
         "  --culling on|off     skip VSGLs whose bounds stay within a budget of the light "
         "(default "
         "off;\n"
         "                       docs/techniques/vsgl-culling.md)\n"
         "  --culling-budget T   that budget, the light a pixel may lose, 0..0.5 (default 0.01)\n"
         "  --planar-emitters on|off  flat VSGLs emit nothing below or along their plane\n"
         "                       (default on; docs/techniques/planar-emitters.md)\n"
         "  --debug-vsgl N       VSGL whose visibility is drawn (default: the most powerful)\n"
         "environment light (docs/techniques/environment.md):\n"
         "  --environment NAME|FILE  a built-in environment (sky, studio, white) or an\n"
         "                       equirectangular HDR/EXR file, y up (default: none)\n"
         "  --env-method NAME    fis (filtered importance sampling, default) or sg (SG lights\n"
         "                       sampled from the environment)\n"
         "  --env-lights N       SG lights, 1..4096 (default 64)\n"
         "  --env-samples N      FIS samples per pixel, 1..4096 (default 40)\n"
         "  --env-sampling MODE  filtered (default), unfiltered or randomised\n"
         "  --env-brdf NAME      ggx (the G-buffer's, default), phong or ward\n";
}

uint32_t shadowResolutionFor(const Options& o) {
  if (o.shadowsFromModule) return o.gi.rsmSize;
  if (o.shadowResolution != 0) return o.shadowResolution;
  uint32_t half = std::max(o.width, o.height) / 2;
  uint32_t resolution = 256;
  while (resolution < half && resolution < 2048) resolution *= 2;
  return resolution;
}

// --planner off: every decision of the effect planner off.
gi::PlannerSettings plannerOff() {
  gi::PlannerSettings p;
  p.skipWithoutBounce = p.skipSky = p.skipWithoutOccluders = p.skipGlossyWithoutSpecular = false;
  return p;
}

Options parseOptions(int argc, char** argv) {
  Options o;
  // Shading costs ~N x pixels (0.3-0.6 us per pair on lavapipe): 128 VSGLs keep the default run
  // under a minute on 2 cores.
  o.gi.vsglCount = 128;
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
      o.width = parseUint(arg, args.value(), 1, 8192);
    else if (arg == "--height")
      o.height = parseUint(arg, args.value(), 1, 8192);
    else if (arg == "--frames")
      o.frames = parseUint(arg, args.value(), 1, 1000);
    else if (arg == "--warmup")
      o.warmup = parseUint(arg, args.value(), 0, 100);
    else if (arg == "--motion")
      o.motion = parseChoice<samples::Motion>(arg, args.value(),
                                              {{"static", samples::Motion::Static},
                                               {"orbit", samples::Motion::Orbit},
                                               {"sweep", samples::Motion::Sweep},
                                               {"move", samples::Motion::Move}});
    else if (arg == "--reuse")
      o.gi.reuse = parseChoice<bool>(arg, args.value(), {{"on", true}, {"off", false}});
    else if (arg == "--shadow-res")
      o.shadowResolution = parseUint(arg, args.value(), 16, 4096);
    else if (arg == "--no-shadows")
      o.shadows = false;
    else if (arg == "--shadows")
      o.shadowsFromModule =
          parseChoice<bool>(arg, args.value(), {{"own", false}, {"module", true}});
    else if (arg == "--exposure")
      o.exposureEv = parseFloat(arg, args.value(), -64.0f, 64.0f);
    else if (arg == "--device")
      o.device = args.value();
    else if (arg == "--list-devices")
      o.listDevices = true;
    else if (arg == "--validation")
      o.validation = true;
    else if (arg == "--export-gltf")
      o.exportGltf = args.value();
    else if (arg == "--no-indirect")
      o.indirect = false;
    else if (arg == "--settings")  // over the defaults and earlier options; later ones win
      o.gi = samples::readSettingsFile(std::string(args.value()), o.gi);
    else if (arg == "--method")
      std::tie(o.gi.method, o.gi.rule) = parseChoice<std::pair<gi::VsglMethod, gi::KernelRule>>(
          arg, args.value(),
          {{"modified", {gi::VsglMethod::FilteredImportanceSampling, gi::KernelRule::Modified}},
           {"tok15", {gi::VsglMethod::FilteredImportanceSampling, gi::KernelRule::Tok15}},
           {"kmeans-2d", {gi::VsglMethod::KmeansImage, gi::KernelRule::Modified}},
           {"kmeans-3d", {gi::VsglMethod::KmeansWorld, gi::KernelRule::Modified}},
           {"vpl", {gi::VsglMethod::Vpl, gi::KernelRule::Modified}}});
    else if (arg == "--kmeans-iterations")
      o.gi.kmeans.iterations = parseUint(arg, args.value(), 1, 64);
    else if (arg == "--kmeans-weights")
      o.gi.kmeans.pdfWeighted =
          parseChoice<bool>(arg, args.value(), {{"pdf", true}, {"uniform", false}});
    else if (arg == "--kmeans-fresh")
      o.gi.kmeans.temporal = false;
    else if (arg == "--pdf")
      o.gi.pdf = parseChoice<gi::PdfKind>(
          arg, args.value(), {{"brsm", gi::PdfKind::Brsm}, {"flux", gi::PdfKind::Flux}});
    else if (arg == "--count")
      o.gi.vsglCount = parseUint(arg, args.value(), 1, gi::kMaxVsglCount);
    else if (arg == "--k")
      o.gi.kernelScale = parseFloat(arg, args.value(), 1.0f, 65536.0f);
    else if (arg == "--rsm")
      o.gi.rsmSize = parseUint(arg, args.value(), 16, 2048);
    else if (arg == "--ism")
      o.gi.ismEnabled = parseChoice<bool>(arg, args.value(), {{"on", true}, {"off", false}});
    else if (arg == "--ism-size")
      o.gi.ism.mapSize = parseUint(arg, args.value(), 16, 256);
    else if (arg == "--no-glossy")
      o.gi.glossy = false;
    else if (arg == "--planner")  // every planner decision at once, for comparison
      o.gi.planner = parseChoice<gi::PlannerSettings>(
          arg, args.value(), {{"on", gi::PlannerSettings{}}, {"off", plannerOff()}});
    else if (arg == "--adaptive")
      o.gi.adaptive.enabled = parseChoice<bool>(arg, args.value(), {{"on", true}, {"off", false}});
    else if (arg == "--adaptive-level")
      o.gi.adaptive.coarsestLevel = parseUint(arg, args.value(), 0, 3);
    else if (arg == "--environment")
      o.environment = args.value();
    else if (arg == "--env-method")
      o.gi.environment.method = parseChoice<gi::EnvironmentMethod>(
          arg, args.value(),
          {{"fis", gi::EnvironmentMethod::Fis}, {"sg", gi::EnvironmentMethod::SgLights}});
    else if (arg == "--env-lights")
      o.gi.environment.sgLightCount = parseUint(arg, args.value(), 1, 4096);
    else if (arg == "--env-samples")
      o.gi.environment.sampleCount = parseUint(arg, args.value(), 1, 4096);
    else if (arg == "--env-sampling")
      o.gi.environment.sampling = parseChoice<gi::EnvironmentSampling>(
          arg, args.value(),
          {{"filtered", gi::EnvironmentSampling::Filtered},
           {"unfiltered", gi::EnvironmentSampling::Unfiltered},
           {"randomised", gi::EnvironmentSampling::Randomised}});
    else if (arg == "--env-brdf")
      o.gi.environment.brdf =
          parseChoice<gi::EnvironmentBrdf>(arg, args.value(),
                                           {{"ggx", gi::EnvironmentBrdf::Ggx},
                                            {"phong", gi::EnvironmentBrdf::Phong},
                                            {"ward", gi::EnvironmentBrdf::Ward}});
    else if (arg == "--culling")
      o.gi.culling.enabled = parseChoice<bool>(arg, args.value(), {{"on", true}, {"off", false}});
    else if (arg == "--planar-emitters")
      o.gi.planarEmitters = parseChoice<bool>(arg, args.value(), {{"on", true}, {"off", false}});
    else if (arg == "--culling-budget")
      o.gi.culling.budget = parseFloat(arg, args.value(), 0.0f, 0.5f);
    else if (arg == "--adaptive-tolerance")
      o.gi.adaptive.lightTolerance = parseFloat(arg, args.value(), 0.0f, 10.0f);
    else if (arg == "--debug-vsgl")
      o.debugVsgl = static_cast<int32_t>(parseUint(arg, args.value(), 0, 65535));
    else if (arg == "--help" || arg == "-h")
      o.help = true;
    else
      throw engine::Error(std::string(arg) + ": unknown option (see --help)");
  }
  if (o.outDir.empty()) throw engine::Error("--out: empty path");
  // The RSM's BRSM grid follows a smaller --rsm; cross-field limits are the library's own.
  o.gi.brsm.gridSize = std::min(o.gi.brsm.gridSize, o.gi.rsmSize);
  if (o.debugVsgl >= static_cast<int32_t>(o.gi.vsglCount))
    throw engine::Error("--debug-vsgl: " + std::to_string(o.debugVsgl) + " is not below --count " +
                        std::to_string(o.gi.vsglCount));
  if (std::string bad = gi::validateSettings(o.gi); !bad.empty()) throw engine::Error(bad);
  if (o.shadowsFromModule && o.shadowResolution != 0)
    throw engine::Error(
        "--shadow-res: with --shadows module the shadow maps are the RSM's size "
        "(--rsm)");
  if (o.shadowsFromModule && (!o.indirect || !o.shadows))
    throw engine::Error(
        "--shadows module: needs the module's light views and shadows (not with "
        "--no-indirect or --no-shadows)");
  return o;
}

}  // namespace render
