// Image files through OpenImageIO. Writers never leave a half-written file behind: they write
// to "<path>.tmp-<pid>" in the same directory and rename it over <path> only on success, so an
// earlier good output survives any failure.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/scene.h"

namespace engine {

// Linear HDR image, RGBA float, rows top to bottom.
struct ImageRgba32f {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // width * height * 4
};

// Writes a linear half-float RGBA OpenEXR file. Throws engine::Error("<path>: <problem>").
void writeExr(const std::string& path, const ImageRgba32f& image);

// Writes an 8-bit RGBA PNG from bytes already encoded (e.g. tone-mapped sRGB).
void writePng(const std::string& path, int width, int height, std::span<const uint8_t> rgba8);
// Writes an animated GIF of sRGB RGBA8 frames (each width x height, as writePng takes them),
// looping forever, written whole or not at all like the others. GIF keeps 256 colours a frame.
void writeAnimatedGif(const std::string& path, int width, int height,
                      std::span<const std::vector<uint8_t>> frames, int framesPerSecond);

// Reads any image OpenImageIO understands, converted to float RGBA (missing channels: G=B=R for
// grey, A=1). Pixel values are the file's own (no colour-space conversion).
ImageRgba32f readImage(const std::string& path);

// How large a decoded texture needs to be. An image whose longer side exceeds maxSize is reduced
// while it is read: each block of f x f texels is averaged, f the largest power of two that
// keeps the longer side >= maxSize (blocks at the right and bottom edges average what they
// hold). It is read a strip of f rows at a time, so memory holds the result and one strip, never
// the whole image. `srgb` averages colour in linear space (a base-colour texture). 0 = full size.
struct TextureSize {
  int maxSize = 0;
  bool srgb = false;
};

// Decodes an encoded image (PNG, JPEG, ...) held in memory into 8-bit RGBA. `name` appears in
// error messages. Throws engine::Error("<name>: <problem>").
Texture decodeTexture(const std::string& name, std::span<const uint8_t> encoded,
                      TextureSize size = {});

// Reads an image file as an 8-bit RGBA texture. Throws engine::Error("<path>: <problem>").
Texture readTexture(const std::string& path);

}  // namespace engine
