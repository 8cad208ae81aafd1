// A recorded view path: the camera and the lights of every frame the interactive viewer
// (vsgl_viewer) rendered, kept in a small text file, so that vsgl_flicker can replay exactly
// what a person flew through (`--motion path --path FILE`, docs/flicker.md). Only what the
// renderer needs to see a frame again is recorded: the names of the lights and of the camera are
// not (a replay does not need them; read lights and cameras have empty names).
//
// The text of a path:
//   # vsgl view path v1
//   frame <index>
//   camera <16 numbers of cameraToWorld, column-major> <perspective 0|1> <yfov> <aspectRatio>
//          <znear> <zfar> <xmag> <ymag>
//   light <point|spot|directional> <position xyz> <direction xyz> <color rgb> <intensity>
//         <range> <innerConeAngle> <outerConeAngle>
//   ... (one light line per light, then the next frame line)
// Each entry above is one line of the file (wrapped here for width). The writer separates the
// fields by one space; the reader takes any spaces or tabs, skips blank lines and takes "\r\n"
// line ends. Frame indices count 0, 1, 2, ... Numbers are written as the shortest text that
// reads back as the same float (std::to_chars), so a path read back replays its frames bit for
// bit.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene.h"

namespace samples {

// The most frames a path holds: vsgl_flicker's longest sequence.
constexpr uint32_t kMaxPathFrames = 1000;

// One frame of a recorded path: the camera and every light as the frame had them.
struct PathFrame {
  engine::Camera camera;
  std::vector<engine::Light> lights;  // may be empty (a scene lit by its environment alone)
};

// The lines of one frame ("frame <index>", its camera and its lights), each ending in '\n'.
std::string formatPathFrame(const PathFrame& frame, uint32_t index);

// Appends frames to a path file as they come, so that a recording survives the viewer ending
// abruptly: each frame is flushed to the file when it is added.
class ViewPathWriter {
 public:
  // Truncates the file and writes the header line; throws engine::Error("<path>: cannot write").
  explicit ViewPathWriter(const std::string& path);
  // Writes `frame` as the next frame. Throws engine::Error "<path>: cannot write" when the write
  // fails, and "<path>: more than 1000 frames" rather than write a path readViewPath refuses
  // (stop recording when frames() reaches kMaxPathFrames).
  void add(const PathFrame& frame);
  uint32_t frames() const { return frames_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream file_;
  uint32_t frames_ = 0;
};

// Reads the text of a path (see above). Every problem is an engine::Error with one line,
// "<source>:<line>: <problem>": a missing header, an unknown line kind, a wrong number count, a
// number that is not a number, not finite or beyond a float, frame indices that do not count 0, 1,
// 2, ..., a camera or light line before the first frame, a frame without a camera line or with two,
// no frame at all, an unknown light type, more than kMaxPathFrames frames, and values no frame can
// be rendered with (the glTF loader's rules: a zero-length direction of a spot or directional
// light, a negative intensity, colour or range, spot cones outside 0 <= inner < outer <= pi/2, a
// perspective yfov outside (0, pi), znear <= 0, zfar neither 0 nor > znear, an orthographic
// camera without zfar > znear >= 0 or with xmag or ymag <= 0, a negative aspect ratio).
std::vector<PathFrame> parseViewPath(std::string_view text, const std::string& source);
// parseViewPath of a file's contents, named by its path; "<path>: cannot read" when it cannot be.
std::vector<PathFrame> readViewPath(const std::string& path);

}  // namespace samples
