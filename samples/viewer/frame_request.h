// What the viewer's window asks the render thread for (FrameRequest) and what comes back
// (FrameResult): the scene, camera, lights, settings and picture of one frame.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/image_io.h"
#include "engine/scene.h"
#include "engine/view.h"
#include "gi/indirect_lighting.h"
#include "host_frame.h"

namespace viewer {

// The picture the window shows.
enum class ViewMode : uint32_t {
  Final,            // direct + indirect (+ environment), tone-mapped
  Direct,           // the host's direct light only
  IndirectDiffuse,  // the bounce's diffuse term
  IndirectGlossy,   // the bounce's glossy term
  VsglLobes,        // the VSGL lobes over the frame
  Visibility,       // the ISM visibility of one VSGL (picked with a click)
  Levels,           // adaptive shading's level per pixel
};
constexpr ViewMode kViewModes[] = {
    ViewMode::Final,     ViewMode::Direct,     ViewMode::IndirectDiffuse, ViewMode::IndirectGlossy,
    ViewMode::VsglLobes, ViewMode::Visibility, ViewMode::Levels};
// The mode's word in scripts and on the command line ("final", "direct", "diffuse", "glossy",
// "lobes", "visibility", "levels").
const char* viewModeWord(ViewMode mode);
// The mode of a word; throws engine::Error naming the accepted words for anything else.
ViewMode parseViewMode(const std::string& option, const std::string& word);

struct FrameRequest {
  uint64_t serial = 0;  // increases with every change; a result carries the one it shows
  // The geometry and materials; the render thread uploads them when the pointer changes. Its
  // lights and cameras are not used: those below are.
  std::shared_ptr<const engine::Scene> scene;
  std::vector<engine::Light> lights;
  engine::Camera camera;
  uint32_t width = 0, height = 0;
  gi::Settings settings;
  // Split screen: the right half shows these settings (another method, say), same camera.
  std::optional<gi::Settings> right;
  bool indirect = true;     // off: direct light only
  std::string environment;  // --environment's argument; "" = none
  std::shared_ptr<const engine::ImageRgba32f> environmentImage;  // loaded by AppState
  ViewMode mode = ViewMode::Final;
  // A pixel whose strongest VSGL (unshadowed) becomes the one the Visibility view shows.
  std::optional<std::array<uint32_t, 2>> pick;
  std::optional<float> exposureEv;  // empty: auto-exposure of the final frame
  bool continuous = true;           // render again when nothing changed (the timing graph runs)
};

struct FrameResult {
  uint64_t serial = 0;
  uint64_t frameNumber = 0;  // frames rendered so far, this one included
  // The picture shown: width x height RGBA8, sRGB-encoded.
  std::vector<uint8_t> rgba;
  uint32_t width = 0, height = 0;
  samples::FrameImages images;  // the left (or only) method's frame, linear
  engine::View view;
  // The request this frame answers: its scene, camera, lights and settings are what a
  // screenshot or a recorded path writes (the window's state may have moved on).
  FrameRequest request;
  std::vector<gi::PassTime> passes;  // the host's, then the module's ("gi ...", "gi right ...")
  std::vector<std::string> plan;     // the effect planner's decisions, then what reuse kept
  uint32_t vsglCount = 0;
  int32_t visibilityVsgl = -1;  // the VSGL whose visibility the Visibility view shows, or -1
  std::string note;             // one line about the frame (e.g. no light bounces)
  std::string error;            // the request failed; the frame before it is still shown
};

}  // namespace viewer
