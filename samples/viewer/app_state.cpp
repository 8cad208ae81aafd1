#include "app_state.h"

#include <cmath>

#include "scene_files.h"
#include "settings_fields.h"

namespace viewer {

std::string AppState::load(const std::string& name, const std::string& cameraChoice) {
  try {
    auto loaded = std::make_shared<engine::Scene>(samples::loadScene(name));
    samples::selectCamera(*loaded, cameraChoice);
    // The light rule of every sample program (a sun when the file has none), for the
    // window's aspect ratio of 16:9 as the headlight's cone needs one.
    status = samples::applyLightChoice(*loaded, lightChoice, !environment.empty(), 16.0f / 9.0f);
    lights = loaded->lights;
    camera.reset(loaded->cameras.empty() ? engine::defaultCamera(*loaded) : loaded->cameras.front(),
                 loaded->bounds());
    scene = std::move(loaded);
    sceneName = name;
    selectedLight = 0;
    changed();
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string AppState::setEnvironment(const std::string& name) {
  try {
    environmentImage =
        name.empty() ? nullptr
                     : std::make_shared<const engine::ImageRgba32f>(samples::loadEnvironment(name));
    environment = name;
    changed();
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

FrameRequest AppState::request(uint32_t width, uint32_t height) {
  FrameRequest r;
  r.serial = serial;
  r.scene = scene;
  r.lights = lights;
  r.camera = camera.camera();
  r.width = width;
  r.height = height;
  r.settings = settings;
  if (!split.empty()) r.right = withMethod(settings, "split", split);
  r.indirect = indirect;
  r.environment = environment;
  r.environmentImage = environmentImage;
  r.mode = mode;
  r.pick = pick;
  pick.reset();
  r.exposureEv = exposureEv;
  r.continuous = continuous;
  return r;
}

void AppState::moveLight(const glm::vec3& d) {
  if (selectedLight >= lights.size()) return;
  lights[selectedLight].position += d;
  changed();
}

void AppState::turnLight(float yawDegrees, float pitchDegrees) {
  if (selectedLight >= lights.size()) return;
  glm::vec3& dir = lights[selectedLight].direction;
  float yaw = std::atan2(-dir.x, -dir.z);
  float pitch = std::asin(std::clamp(dir.y / glm::length(dir), -1.0f, 1.0f));
  yaw += glm::radians(yawDegrees);
  pitch = std::clamp(pitch + glm::radians(pitchDegrees), -1.5607f, 1.5607f);
  dir = {-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
  changed();
}

std::string AppState::apply(const ScriptEvent& e) {
  const std::string& c = e.command;
  if (c == "scene") {
    if (std::string error = load(e.args[0], ""); !error.empty()) return error;
  } else if (c == "environment") {
    const std::string name = e.args[0] == "none" ? "" : e.args[0];
    if (std::string error = setEnvironment(name); !error.empty()) return error;
  } else if (c == "orbit") {
    camera.turn(scriptNumber(e, 0), scriptNumber(e, 1));
  } else if (c == "zoom") {
    camera.zoom(scriptNumber(e, 0));
  } else if (c == "move") {
    camera.move({scriptNumber(e, 0), scriptNumber(e, 1), scriptNumber(e, 2)});
  } else if (c == "light") {
    const float index = scriptNumber(e, 0);
    if (index < 0.0f || index >= float(lights.size()) || index != std::floor(index))
      throw engine::Error("line " + std::to_string(e.line) + ": light " + e.args[0] +
                          ": the scene has " + std::to_string(lights.size()) + " light(s)");
    selectedLight = uint32_t(index);
  } else if (c == "light-move") {
    moveLight({scriptNumber(e, 0), scriptNumber(e, 1), scriptNumber(e, 2)});
  } else if (c == "light-turn") {
    turnLight(scriptNumber(e, 0), scriptNumber(e, 1));
  } else if (c == "set") {
    settings = samples::parseSettings(e.args[0] + " = " + e.args[1],
                                      "line " + std::to_string(e.line), settings);
  } else if (c == "view") {
    mode = parseViewMode("view", e.args[0]);
  } else if (c == "split") {
    split = e.args[0] == "off" ? "" : methodWord(withMethod(settings, "split", e.args[0]));
  } else if (c == "pick") {
    pick = std::array<uint32_t, 2>{uint32_t(std::max(scriptNumber(e, 0), 0.0f)),
                                   uint32_t(std::max(scriptNumber(e, 1), 0.0f))};
  }
  changed();
  return {};
}

AppState initialState(const Options& o) {
  AppState s;
  s.settings = o.gi;
  s.split = o.split;
  if (std::string error = s.setEnvironment(o.environment); !error.empty())
    throw engine::Error(error);
  s.mode = o.mode;
  s.exposureEv = o.exposureEv;
  s.scale = o.scale;
  s.lightChoice = o.light;
  // A script or a fixed frame count renders one frame per step (script.h).
  s.continuous = o.script.empty() && o.frames == 0;
  if (std::string error = s.load(o.scene, o.camera); !error.empty()) throw engine::Error(error);
  return s;
}

}  // namespace viewer
