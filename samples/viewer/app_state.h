// What a person controls in vsgl_viewer, apart from the window: the scene and its lights, the
// camera, the module's settings and the picture. The panel, the mouse and keys, and scripts all
// change it through the same functions, so a script replays what a person does.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera_control.h"
#include "frame_request.h"
#include "options.h"
#include "script.h"

namespace viewer {

struct AppState {
  std::string sceneName;  // --scene's argument of the scene shown
  std::shared_ptr<const engine::Scene> scene;
  std::vector<engine::Light> lights;  // as moved and turned
  CameraControl camera;
  uint32_t selectedLight = 0;
  gi::Settings settings;
  std::string split;  // "" or the right half's method word
  bool indirect = true;
  std::string environment;  // --environment's argument, "" = none
  std::shared_ptr<const engine::ImageRgba32f> environmentImage;
  ViewMode mode = ViewMode::Final;
  std::optional<float> exposureEv;
  float scale = 0.5f;
  bool continuous = true;
  samples::LightChoice lightChoice = samples::LightChoice::Auto;
  std::optional<std::array<uint32_t, 2>> pick;  // sent with the next request
  uint64_t serial = 0;                          // bumped by every change
  std::string status;  // the last message for the panel (a load that failed, a screenshot)

  // Loads a built-in scene or file and selects `camera` ("" = the first). On failure the
  // current scene stays and the error is returned ("" on success).
  std::string load(const std::string& name, const std::string& camera);
  // Loads a built-in environment or an image file ("" = none). On failure the current
  // environment stays and the error is returned ("" on success).
  std::string setEnvironment(const std::string& name);
  void changed() { ++serial; }
  // The request for a frame of width x height.
  FrameRequest request(uint32_t width, uint32_t height);
  // Moves the selected light by `d` (world axes, metres) / turns its direction, degrees.
  void moveLight(const glm::vec3& d);
  void turnLight(float yawDegrees, float pitchDegrees);
  // Applies one scripted event (script.h); "screenshot" is the caller's. Returns a problem that
  // leaves the state as it was (a scene that fails to load), else "".
  std::string apply(const ScriptEvent& event);
};

AppState initialState(const Options& options);

}  // namespace viewer
