// Command line of vsgl_viewer. Every option is validated here, so that a bad value fails with
// one line before a window opens.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cli_values.h"
#include "default_light.h"
#include "frame_request.h"
#include "gi/settings.h"

namespace viewer {

struct Options {
  std::string scene = "cornell";  // built-in scene name or a .gltf/.glb path
  std::string environment;        // built-in name or HDR/EXR file; "" = none
  samples::LightChoice light = samples::LightChoice::Auto;
  std::string camera;                   // the file's camera; "" = the first
  uint32_t width = 1280, height = 720;  // the window, pixels
  // The frame is rendered at the window's size times this, [0.1, 1] (lavapipe: 0.5 keeps a
  // 1280 x 720 window near two frames a second with 128 VSGLs on two cores).
  float scale = 0.5f;
  gi::Settings gi;
  std::string split;  // "" = no split screen, else a method word (methodWords())
  ViewMode mode = ViewMode::Final;
  std::string script;   // --script FILE (script.h)
  uint32_t frames = 0;  // --frames N: quit after N rendered frames (0 = run until closed)
  // The panel's frames per second at most, [5, 240]: on a CPU device the panel's drawing takes
  // the cores the frame renders on, so it is capped (docs/viewer.md has the trade).
  uint32_t panelFps = 30;
  float seconds = 0.0f;    // --seconds S: quit after S seconds, rendering as a person would see
                           // it (0 = run until closed); for measuring the panel's rate
  std::string screenshot;  // --screenshot BASE: written after the last frame
  std::string record;      // --record FILE: the camera and lights of every frame (view_path.h)
  std::optional<float> exposureEv;
  samples::CommonOptions common;  // --device, --validation, --help
};

Options parseOptions(int argc, char** argv);
const char* usage();

// The method words of --method and --split: modified, tok15, kmeans-2d, kmeans-3d, vpl.
const char* const* methodWords();
// `settings` with the method of `word`; throws engine::Error("<option>: ...") naming the words.
gi::Settings withMethod(gi::Settings settings, const std::string& option, const std::string& word);
// The word of `settings`'s method.
const char* methodWord(const gi::Settings& settings);

}  // namespace viewer
