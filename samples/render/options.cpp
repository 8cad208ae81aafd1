#include "options.h"

#include <algorithm>
#include <string_view>

#include "cli_values.h"
#include "engine/error.h"

namespace render {

using samples::parseFloat;
using samples::parseUint;
const char* usage() {
  return "usage: vsgl_render [options]\n"
         "  --scene NAME|FILE    built-in scene (cornell, atrium, checker) or .gltf/.glb (default "
         "cornell)\n"
         "  --out DIR            output directory (default out)\n"
         "  --width N --height N image size in pixels, 1..8192 (default 640x360)\n"
         "  --frames N           measured frames after one warm-up frame, 1..1000 (default 5)\n"
         "  --shadow-res N       shadow-map texels per side, 16..4096 (default: from the image "
         "size)\n"
         "  --no-shadows         direct light without shadow maps\n"
         "  --exposure EV        fixed exposure in stops for the PNG (default: auto)\n"
         "  --device SEL         Vulkan device index or name substring (default: VSGL_DEVICE or "
         "auto)\n"
         "  --list-devices       print the Vulkan devices and exit\n"
         "  --validation         enable the Khronos validation layer\n"
         "  --export-gltf PATH   also write the scene as a .gltf file\n";
}

uint32_t shadowResolutionFor(const Options& o) {
  if (o.shadowResolution != 0) return o.shadowResolution;
  uint32_t half = std::max(o.width, o.height) / 2;
  uint32_t resolution = 256;
  while (resolution < half && resolution < 2048) resolution *= 2;
  return resolution;
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw engine::Error(std::string(arg) + ": missing value");
      return argv[++i];
    };
    if (arg == "--scene")
      o.scene = value();
    else if (arg == "--out")
      o.outDir = value();
    else if (arg == "--width")
      o.width = parseUint(arg, value(), 1, 8192);
    else if (arg == "--height")
      o.height = parseUint(arg, value(), 1, 8192);
    else if (arg == "--frames")
      o.frames = parseUint(arg, value(), 1, 1000);
    else if (arg == "--shadow-res")
      o.shadowResolution = parseUint(arg, value(), 16, 4096);
    else if (arg == "--no-shadows")
      o.shadows = false;
    else if (arg == "--exposure")
      o.exposureEv = parseFloat(arg, value(), -64.0f, 64.0f);
    else if (arg == "--device")
      o.device = value();
    else if (arg == "--list-devices")
      o.listDevices = true;
    else if (arg == "--validation")
      o.validation = true;
    else if (arg == "--export-gltf")
      o.exportGltf = value();
    else if (arg == "--help" || arg == "-h")
      o.help = true;
    else
      throw engine::Error(std::string(arg) + ": unknown option (see --help)");
  }
  if (o.outDir.empty()) throw engine::Error("--out: empty path");
  return o;
}

}  // namespace render
