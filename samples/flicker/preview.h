// vsgl_flicker's pictures of a capture: every row (the reference, then each method) tone-mapped
// with the capture's one exposure, so that brightness changes are the images' own. Only the
// frames the pictures show are kept (previewFrames), as 8-bit tiles, so that a long capture does
// not hold every frame in memory.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace flicker {

// Which of a sequence's `frames` the pictures show: all of them up to 48, else 48 spread evenly
// (first and last included), in order.
std::vector<uint32_t> previewFrames(uint32_t frames);

struct PreviewRow {
  std::string name;
  std::vector<std::vector<uint8_t>> frames;  // tone-mapped RGBA8 of the previewFrames, in order
};

struct Preview {
  int width = 0, height = 0;  // of one tile
  std::vector<PreviewRow> rows;
};

// A strip: one line of tiles per row, 8 of the kept frames spread left to right.
void writeStrip(const std::string& path, const Preview& preview);
// An animated GIF at 8 frames per second: each kept frame shows every row side by side.
void writeGif(const std::string& path, const Preview& preview);

}  // namespace flicker
