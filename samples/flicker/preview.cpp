#include "preview.h"

#include <algorithm>
#include <cstring>

namespace flicker {
namespace {

constexpr size_t kStripFrames = 8;
constexpr int kGifFramesPerSecond = 8;
constexpr int kGap = 2;  // pixels of black between tiles

// Copies a tone-mapped tile into an RGBA8 canvas `canvasWidth` wide at (x, y).
void blit(std::vector<uint8_t>& canvas, int canvasWidth, int x, int y,
          const engine::ImageRgba32f& image, const engine::ToneMapSettings& toneMap) {
  const std::vector<uint8_t> tile = engine::toneMap(image, toneMap);
  for (int row = 0; row < image.height; ++row)
    std::memcpy(&canvas[(size_t(y + row) * canvasWidth + x) * 4],
                &tile[size_t(row) * image.width * 4], size_t(image.width) * 4);
}

}  // namespace

void writeStrip(const std::string& path, const std::vector<PreviewRow>& rows,
                const engine::ToneMapSettings& toneMap) {
  const size_t frames = rows.front().frames.size();
  const size_t columns = std::min(frames, kStripFrames);
  const int w = rows.front().frames.front().width, h = rows.front().frames.front().height;
  const int width = int(columns) * (w + kGap) - kGap, height = int(rows.size()) * (h + kGap) - kGap;
  std::vector<uint8_t> canvas(size_t(width) * height * 4, 0);
  for (size_t i = 0; i < canvas.size(); i += 4) canvas[i + 3] = 255;
  for (size_t r = 0; r < rows.size(); ++r)
    for (size_t c = 0; c < columns; ++c) {
      const size_t t = columns > 1 ? c * (frames - 1) / (columns - 1) : 0;
      blit(canvas, width, int(c) * (w + kGap), int(r) * (h + kGap), rows[r].frames[t], toneMap);
    }
  engine::writePng(path, width, height, canvas);
}

void writeGif(const std::string& path, const std::vector<PreviewRow>& rows,
              const engine::ToneMapSettings& toneMap) {
  const size_t frames = rows.front().frames.size();
  const int w = rows.front().frames.front().width, h = rows.front().frames.front().height;
  const int width = int(rows.size()) * (w + kGap) - kGap;
  std::vector<std::vector<uint8_t>> pictures;
  for (size_t t = 0; t < frames; ++t) {
    std::vector<uint8_t> canvas(size_t(width) * h * 4, 0);
    for (size_t i = 0; i < canvas.size(); i += 4) canvas[i + 3] = 255;
    for (size_t r = 0; r < rows.size(); ++r)
      blit(canvas, width, int(r) * (w + kGap), 0, rows[r].frames[t], toneMap);
    pictures.push_back(std::move(canvas));
  }
  engine::writeAnimatedGif(path, width, h, pictures, kGifFramesPerSecond);
}

}  // namespace flicker
