// vsgl_flicker's pictures of a capture: every row (the reference, then each method) tone-mapped
// with the capture's one exposure, so that brightness changes are the images' own.
#pragma once

#include <string>
#include <vector>

#include "engine/image_io.h"
#include "engine/tonemap.h"

namespace flicker {

struct PreviewRow {
  std::string name;
  std::vector<engine::ImageRgba32f> frames;  // linear, all of one size
};

// A strip: one line of tiles per row, up to 8 frames spread over the sequence left to right.
void writeStrip(const std::string& path, const std::vector<PreviewRow>& rows,
                const engine::ToneMapSettings& toneMap);
// An animated GIF at 8 frames per second: frame t shows every row's frame t side by side.
void writeGif(const std::string& path, const std::vector<PreviewRow>& rows,
              const engine::ToneMapSettings& toneMap);

}  // namespace flicker
