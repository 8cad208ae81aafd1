#include "preview.h"

#include <algorithm>
#include <cstring>

#include "engine/image_io.h"

namespace flicker {
namespace {

constexpr uint32_t kPreviewFrames = 48;
constexpr size_t kStripFrames = 8;
constexpr int kGifFramesPerSecond = 8;
constexpr int kGap = 2;  // pixels of black between tiles

// An opaque black RGBA8 canvas.
std::vector<uint8_t> blackCanvas(int width, int height) {
  std::vector<uint8_t> canvas(size_t(width) * height * 4, 0);
  for (size_t i = 3; i < canvas.size(); i += 4) canvas[i] = 255;
  return canvas;
}

// Copies a w x h RGBA8 tile into a canvas `canvasWidth` wide at (x, y).
void blit(std::vector<uint8_t>& canvas, int canvasWidth, int x, int y, int w, int h,
          const std::vector<uint8_t>& tile) {
  for (int row = 0; row < h; ++row)
    std::memcpy(&canvas[(size_t(y + row) * canvasWidth + x) * 4], &tile[size_t(row) * w * 4],
                size_t(w) * 4);
}

}  // namespace

std::vector<uint32_t> previewFrames(uint32_t frames) {
  std::vector<uint32_t> kept;
  const uint32_t count = std::min(frames, kPreviewFrames);
  for (uint32_t i = 0; i < count; ++i)
    kept.push_back(count > 1 ? uint32_t(uint64_t(i) * (frames - 1) / (count - 1)) : 0u);
  return kept;
}

void writeStrip(const std::string& path, const Preview& p) {
  const size_t frames = p.rows.front().frames.size();
  const size_t columns = std::min(frames, kStripFrames);
  const int width = int(columns) * (p.width + kGap) - kGap;
  const int height = int(p.rows.size()) * (p.height + kGap) - kGap;
  std::vector<uint8_t> canvas = blackCanvas(width, height);
  for (size_t r = 0; r < p.rows.size(); ++r)
    for (size_t c = 0; c < columns; ++c) {
      const size_t t = columns > 1 ? c * (frames - 1) / (columns - 1) : 0;
      blit(canvas, width, int(c) * (p.width + kGap), int(r) * (p.height + kGap), p.width, p.height,
           p.rows[r].frames[t]);
    }
  engine::writePng(path, width, height, canvas);
}

void writeGif(const std::string& path, const Preview& p) {
  const int width = int(p.rows.size()) * (p.width + kGap) - kGap;
  std::vector<std::vector<uint8_t>> pictures;
  for (size_t t = 0; t < p.rows.front().frames.size(); ++t) {
    std::vector<uint8_t> canvas = blackCanvas(width, p.height);
    for (size_t r = 0; r < p.rows.size(); ++r)
      blit(canvas, width, int(r) * (p.width + kGap), 0, p.width, p.height, p.rows[r].frames[t]);
    pictures.push_back(std::move(canvas));
  }
  engine::writeAnimatedGif(path, width, p.height, pictures, kGifFramesPerSecond);
}

}  // namespace flicker
