// The animated sequences of vsgl_flicker (docs/flicker.md) and vsgl_render --motion: the scene,
// camera and light of frame t of a motion. Each motion moves one thing, so that a capture shows
// the flicker, and a timing the cost, that one kind of change causes:
//   static  nothing moves (every flicker figure must be exactly 0: the pipeline is deterministic)
//   orbit   the camera turns 30 degrees about the vertical axis through the scene's centre: the
//           view-dependent BRSM PDF changes, the RSM does not
//   sweep   the first spot or directional light turns 20 degrees about the vertical axis: its
//           RSM itself changes (every light bounces; the others stay)
//   move    a box, added to the scene, slides across the floor (a third of the scene's width)
//   path    a recorded view path (samples/common/view_path.h) replayed: frame t has the file's
//           camera and lights of its frame t (the scene's own lights are replaced), so that a
//           capture shows the flicker of a flight a person made in vsgl_viewer
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/scene.h"
#include "engine/view.h"
#include "view_path.h"

namespace samples {

enum class Motion { Static, Orbit, Sweep, Move, Path };

// --motion's words; throws engine::Error naming them for anything else.
Motion parseMotion(const std::string& word);

struct Frame {
  engine::Scene scene;  // with the light turned (sweep), the box placed (move) or the path's lights
  engine::View view;
};

// The index of the light sweep turns: the first spot or directional light of `scene` (a point
// light has no direction to turn). Throws engine::Error naming the scene when it has none.
uint32_t sweptLight(const engine::Scene& scene);

// Frame t of `frames` (t = 0 .. frames - 1) of `motion` applied to `base`, seen at
// width x height. `path` holds the recorded frames of Motion::Path (frames of them; nullptr for
// the other motions).
Frame makeFrame(const engine::Scene& base, Motion motion, uint32_t t, uint32_t frames,
                uint32_t width, uint32_t height, const std::vector<PathFrame>* path);

}  // namespace samples
