// Command line of vsgl_render. Every option is validated here, so a bad value fails with a
// one-line message before any work (or output) happens.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace render {

struct Options {
  std::string scene = "cornell";  // built-in scene name or a .gltf/.glb path
  std::string outDir = "out";
  uint32_t width = 640;
  uint32_t height = 360;
  uint32_t frames = 5;             // measured frames after one warm-up frame
  uint32_t shadowResolution = 1024;
  bool shadows = true;
  std::optional<float> exposureEv;
  std::string device;              // index or name substring (else VSGL_DEVICE, else automatic)
  bool validation = false;
  bool listDevices = false;
  std::string exportGltf;          // write the (built-in) scene as .gltf to this path
  bool help = false;
};

// Throws engine::Error("<option>: <problem>") on a bad command line.
Options parseOptions(int argc, char** argv);
const char* usage();

}  // namespace render
