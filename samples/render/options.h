// Command line of vsgl_render. Every option is validated here, so a bad value fails with a
// one-line message before any work (or output) happens.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "default_light.h"
#include "gi/settings.h"
#include "motion.h"

namespace render {

struct Options {
  std::string scene = "cornell";  // built-in scene name or a .gltf/.glb path
  std::string outDir = "out";
  uint32_t width = 640;
  uint32_t height = 360;
  uint32_t frames = 3;  // measured frames
  uint32_t warmup = 1;  // unmeasured frames before them
  // What moves over the warm-up and measured frames (samples/common/motion.h; not Path).
  samples::Motion motion = samples::Motion::Static;
  uint32_t shadowResolution = 0;  // 0 = automatic: see shadowResolutionFor()
  bool shadows = true;
  // The direct light's shadow maps are the module's light views (gi::FrameOutput::lightViews)
  // where it has them, at the RSM's size: one triangle setup per light and frame.
  bool shadowsFromModule = false;
  std::optional<float> exposureEv;
  std::string device;  // index or name substring (else VSGL_DEVICE, else automatic)
  bool validation = false;
  bool listDevices = false;
  std::string exportGltf;  // write the (built-in) scene as .gltf to this path
  bool help = false;
  // Indirect light through the public API (gi/include); indirect = false renders direct only.
  bool indirect = true;
  gi::Settings gi;
  // Environment light: a built-in name (engine/environments.h) or an HDR/EXR equirectangular
  // file; empty = none.
  std::string environment;
  samples::LightChoice light = samples::LightChoice::Auto;  // --light
  std::string camera;                                       // --camera; "" = the first
  // VSGL whose ISM visibility becomes the debug picture; -1 = the most powerful one.
  int32_t debugVsgl = -1;
};

// Shadow maps with about as many texels across the lit area as the image has pixels: the
// power of two at or above half the image's larger side, in [256, 2048]. Larger maps cost
// rasterizer time (~ texels) without visible gain at the default viewing distances.
uint32_t shadowResolutionFor(const Options& options);

// Throws engine::Error("<option>: <problem>") on a bad command line.
Options parseOptions(int argc, char** argv);
const char* usage();

}  // namespace render
