// vsgl_viewer's panel (Dear ImGui): the scene, camera and lights; every gi::Settings field, grouped
// as settings.h groups them, with its unit and range; the view; the pass times as a rolling
// graph; the effect planner's decisions. It changes the AppState and asks the main loop for
// what only it can do (a screenshot, a recording).
#pragma once

#include <deque>
#include <map>
#include <string>

#include "app_state.h"
#include "frame_request.h"

namespace viewer {

struct PanelRequests {
  bool screenshot = false;
  bool toggleRecording = false;
};

// The last frames' times for the graphs, oldest first.
struct TimingHistory {
  static constexpr size_t kFrames = 120;
  std::deque<float> module;  // the module's passes (gi ...), ms
  std::deque<float> host;    // the whole frame ("host frame", the module included), ms
  // Each pass's time by name; a pass a frame did not run counts 0 there.
  std::map<std::string, std::deque<float>> passes;
  void add(const FrameResult& result);
};

struct PanelContext {
  std::string device;
  const FrameResult* last = nullptr;  // the newest result shown (or null before the first)
  const TimingHistory* history = nullptr;
  bool recording = false;
  float uiFps = 0.0f;
  uint32_t renderWidth = 0, renderHeight = 0;
};

PanelRequests drawPanel(AppState& state, const PanelContext& context);

}  // namespace viewer
