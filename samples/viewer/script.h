// Scripted input for vsgl_viewer (--script FILE): the events a person would cause, by frame, so
// that a session can be replayed and tested. One event per line, "<frame> <command> [args]",
// '#' starts a comment; frames count rendered frames from 0 and must not decrease. In a script
// run every step renders exactly one frame after its events, so the result does not depend on
// how fast the machine is. Commands (angles in degrees, distances in metres):
//   orbit YAW PITCH         turn the camera about its target (fly mode: about the eye)
//   zoom FACTOR             orbit distance times FACTOR (0.1..10)
//   move RIGHT UP FORWARD   move the camera along its axes
//   light INDEX             the light the next light commands change
//   light-move DX DY DZ     move that light (world axes)
//   light-turn YAW PITCH    turn that light's direction (yaw about +y, pitch up)
//   set KEY VALUE           a gi::Settings field (samples/common/settings_fields.h), e.g.
//                           "set vsglCount 256"
//   view MODE               final, direct, diffuse, glossy, lobes, visibility, levels
//   split METHOD|off        the right half with another method (modified, tok15, kmeans-2d,
//                           kmeans-3d, vpl)
//   pick X Y                the VSGL lighting pixel (X, Y) most becomes the visibility view's
//   scene NAME|FILE         load a built-in scene or a file; one that fails to load leaves the
//                           scene as it was (one line on stderr), as the panel's Load button
//   environment NAME|FILE|none  a built-in environment or an HDR/EXR file; one that fails to
//                           load leaves the environment as it was, as the scene command
//   screenshot BASE         write BASE.{exr,png}, BASE_window.png, BASE.gltf, BASE.settings
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace viewer {

struct ScriptEvent {
  uint32_t frame = 0;
  std::string command;
  std::vector<std::string> args;  // checked by readScript: counts, numbers, words
  uint32_t line = 0;
};

// Throws engine::Error("<path>:<line>: <problem>") for a line it cannot take.
std::vector<ScriptEvent> readScript(const std::string& path);

// The number argument `i` of an event readScript accepted.
float scriptNumber(const ScriptEvent& event, size_t i);

}  // namespace viewer
