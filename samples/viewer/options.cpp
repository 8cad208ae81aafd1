#include "options.h"

#include <cstring>
#include <string_view>

#include "cli_values.h"
#include "engine/error.h"
#include "scene_files.h"
#include "settings_fields.h"

namespace viewer {
namespace {

struct Method {
  const char* word;
  gi::VsglMethod method;
  gi::KernelRule rule;
};
constexpr Method kMethods[] = {
    {"modified", gi::VsglMethod::FilteredImportanceSampling, gi::KernelRule::Modified},
    {"tok15", gi::VsglMethod::FilteredImportanceSampling, gi::KernelRule::Tok15},
    {"kmeans-2d", gi::VsglMethod::KmeansImage, gi::KernelRule::Modified},
    {"kmeans-3d", gi::VsglMethod::KmeansWorld, gi::KernelRule::Modified},
    {"vpl", gi::VsglMethod::Vpl, gi::KernelRule::Modified},
};
constexpr const char* kMethodWords[] = {"modified",  "tok15", "kmeans-2d",
                                        "kmeans-3d", "vpl",   nullptr};

}  // namespace

const char* const* methodWords() {
  return kMethodWords;
}

gi::Settings withMethod(gi::Settings settings, const std::string& option, const std::string& word) {
  for (const Method& m : kMethods)
    if (word == m.word) {
      settings.method = m.method;
      settings.rule = m.rule;
      return settings;
    }
  throw engine::Error(option + ": '" + word +
                      "' is not one of modified, tok15, kmeans-2d, kmeans-3d, vpl");
}

const char* methodWord(const gi::Settings& settings) {
  for (const Method& m : kMethods)
    if (settings.method == m.method &&
        (m.method != gi::VsglMethod::FilteredImportanceSampling || settings.rule == m.rule))
      return m.word;
  return "?";
}

const char* usage() {
  return "usage: vsgl_viewer [options]\n"
         "  --scene NAME|FILE    built-in scene (cornell, atrium, checker, lounge) or .gltf/.glb\n"
         "                       (default cornell)\n"
         "  --environment NAME|FILE  sky, studio, white or an equirectangular HDR/EXR "
         "file\n" SAMPLES_LIGHT_USAGE SAMPLES_CAMERA_USAGE
         "  --width N --height N window size in pixels, 64..8192 (default 1280x720)\n"
         "  --scale S            the frame's resolution over the window's, 0.1..1 (default 0.5)\n"
         "  --settings FILE      gi::Settings fields, 'key = value' lines (a screenshot's "
         ".settings)\n"
         "  --count N            VSGLs per frame, 1..32768 (default 128)\n"
         "  --method NAME        modified (default), tok15, kmeans-2d, kmeans-3d or vpl\n"
         "  --split NAME         split screen: the right half with that method\n"
         "  --view MODE          final (default), direct, diffuse, glossy, lobes, visibility, "
         "levels\n"
         "  --exposure EV        fixed exposure in stops (default: auto)\n"
         "  --script FILE        scripted input: '<frame> <command> [args]' lines "
         "(docs/viewer.md)\n"
         "  --frames N           quit after N rendered frames, 1..100000 (default: when closed)\n"
         "  --panel-fps N        the panel's frames per second at most, 5..240 (default 30)\n"
         "  --seconds S          run interactively for S seconds, 0.1..86400, then quit and\n"
         "                       print the panel's and the renderer's rates\n"
         "  --screenshot BASE    after the last frame write BASE.{exr,png} (the frame),\n"
         "                       BASE_window.png, BASE.gltf and BASE.settings\n"
         "  --record FILE        record the camera and lights of every frame for vsgl_flicker\n"
         "                       --motion path\n"
         "  --device SEL         Vulkan device index or name substring\n"
         "  --validation         enable the Khronos validation layer\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  o.gi.vsglCount = 128;  // vsgl_render's default: interactive on lavapipe
  for (samples::Arguments args(argc, argv); args.next();) {
    const std::string_view arg = args.option();
    const std::string option(arg);
    if (arg == "--scene")
      o.scene = args.value();
    else if (arg == "--environment")
      o.environment = args.value();
    else if (arg == "--light")
      o.light = samples::parseLightChoice(arg, args.value());
    else if (arg == "--camera")
      o.camera = args.value();
    else if (arg == "--width")
      o.width = samples::parseUint(arg, args.value(), 64, 8192);
    else if (arg == "--height")
      o.height = samples::parseUint(arg, args.value(), 64, 8192);
    else if (arg == "--scale")
      o.scale = samples::parseFloat(arg, args.value(), 0.1f, 1.0f);
    else if (arg == "--settings")
      o.gi = samples::readSettingsFile(std::string(args.value()), o.gi);
    else if (arg == "--count")
      o.gi.vsglCount = samples::parseUint(arg, args.value(), 1, gi::kMaxVsglCount);
    else if (arg == "--method")
      o.gi = withMethod(o.gi, option, std::string(args.value()));
    else if (arg == "--split")
      o.split = methodWord(withMethod(o.gi, option, std::string(args.value())));
    else if (arg == "--view")
      o.mode = parseViewMode(option, std::string(args.value()));
    else if (arg == "--exposure")
      o.exposureEv = samples::parseFloat(arg, args.value(), -64.0f, 64.0f);
    else if (arg == "--script")
      o.script = args.value();
    else if (arg == "--frames")
      o.frames = samples::parseUint(arg, args.value(), 1, 100000);
    else if (arg == "--panel-fps")
      o.panelFps = samples::parseUint(arg, args.value(), 5, 240);
    else if (arg == "--seconds")
      o.seconds = samples::parseFloat(arg, args.value(), 0.1f, 86400.0f);
    else if (arg == "--screenshot")
      o.screenshot = args.value();
    else if (arg == "--record")
      o.record = args.value();
    else
      samples::parseCommonOption(arg, args, o.common);
  }
  if (o.seconds > 0.0f && (o.frames > 0 || !o.script.empty()))
    throw engine::Error("--seconds: not with --frames or --script (they render step by step)");
  if (!o.screenshot.empty() && o.screenshot.back() == '/')
    throw engine::Error("--screenshot: '" + o.screenshot + "' names a directory, not a file base");
  o.gi.brsm.gridSize = std::min(o.gi.brsm.gridSize, o.gi.rsmSize);
  if (std::string bad = gi::validateSettings(o.gi); !bad.empty()) throw engine::Error(bad);
  return o;
}

}  // namespace viewer
