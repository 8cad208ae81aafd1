#include "engine/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string_view>
#include <system_error>

#include "engine/error.h"
#include "engine/tonemap.h"

namespace engine {
namespace {

// A corrupt header can claim billions of pixels; refuse before allocating for them. 2^28 pixels
// (16384^2) is far beyond any texture or output this module handles.
constexpr uint64_t kMaxPixels = uint64_t{1} << 28;

// OpenImageIO reports errors as several lines (plugin message, then library message), and
// sometimes none at all; engine errors are exactly one line.
std::string oiioMessage(const std::string& message) {
  std::string result = joinLines(message);
  return result.empty() ? std::string("unknown OpenImageIO error") : result;
}

// Owns "<path>.tmp-<pid>" until it is renamed over <path>; on any exit without commit it deletes
// the partial file, so a failed write never leaves debris next to the previous good output.
class TempFile {
 public:
  explicit TempFile(const std::string& target)
      : target_(target), path_(target + ".tmp-" + std::to_string(::getpid())) {}
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  ~TempFile() {
    if (committed_) return;
    std::error_code ec;
    // A directory of that name was never created by us (OIIO only writes files): leave it.
    if (!std::filesystem::is_directory(path_, ec)) std::filesystem::remove(path_, ec);
  }

  const std::string& path() const { return path_; }

  // rename() within one directory is atomic on POSIX: readers see the old file or the new one.
  void commit() {
    std::error_code ec;
    std::filesystem::rename(path_, target_, ec);
    if (ec) throw Error(target_ + ": cannot replace file: " + ec.message());
    committed_ = true;
  }

 private:
  std::string target_;
  std::string path_;
  bool committed_ = false;
};

void validateSize(const std::string& path, int width, int height, size_t valueCount) {
  if (width <= 0 || height <= 0) {
    throw Error(path + ": invalid image size " + std::to_string(width) + "x" +
                std::to_string(height));
  }
  const size_t expected = static_cast<size_t>(width) * static_cast<size_t>(height) * 4;
  if (valueCount != expected) {
    throw Error(path + ": expected " + std::to_string(expected) + " RGBA values for " +
                std::to_string(width) + "x" + std::to_string(height) + ", got " +
                std::to_string(valueCount));
  }
}

// The format is forced by name because the temp file's extension (".tmp-<pid>") names none.
void writeAtomically(const std::string& path, const char* format, const OIIO::ImageSpec& spec,
                     OIIO::TypeDesc dataType, const void* data) {
  TempFile temp(path);
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
  if (!out) throw Error(path + ": " + oiioMessage(OIIO::geterror()));
  if (!out->open(temp.path(), spec)) throw Error(path + ": " + oiioMessage(out->geterror()));
  const bool written = out->write_image(dataType, data);
  // close() flushes the encoder, so its failure is a write failure too.
  if (!out->close() || !written) throw Error(path + ": " + oiioMessage(out->geterror()));
  temp.commit();
}

// Reads subimage 0 of an opened image as RGBA of element type T. One channel is grey (replicated
// into RGB); two are grey + alpha, as PNG and TIFF store them; a missing alpha becomes `opaque`.
// Expands n pixels of `channels` (1 to 4) to RGBA: grey to R = G = B, a missing alpha `opaque`.
template <typename T>
void expandToRgba(const T* src, int channels, size_t n, T opaque, T* dst) {
  for (size_t i = 0; i < n; ++i, src += channels, dst += 4) {
    if (channels <= 2) {
      dst[0] = dst[1] = dst[2] = src[0];
      dst[3] = channels == 2 ? src[1] : opaque;
    } else {
      std::copy_n(src, 3, dst);
      dst[3] = channels == 4 ? src[3] : opaque;
    }
  }
}

template <typename T>
std::vector<T> readRgba(OIIO::ImageInput& in, const std::string& name, T opaque, int& width,
                        int& height) {
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.width <= 0 || spec.height <= 0) throw Error(name + ": image has zero size");
  if (spec.depth != 1) throw Error(name + ": volume images are not supported");
  if (spec.nchannels <= 0) throw Error(name + ": image has no channels");
  const uint64_t pixelCount =
      static_cast<uint64_t>(spec.width) * static_cast<uint64_t>(spec.height);
  if (pixelCount > kMaxPixels) {
    throw Error(name + ": image too large (" + std::to_string(spec.width) + "x" +
                std::to_string(spec.height) + ")");
  }

  const int channels = std::min(spec.nchannels, 4);
  std::vector<T> source(pixelCount * static_cast<uint64_t>(channels));
  if (!in.read_image(0, 0, 0, channels, OIIO::BaseTypeFromC<T>::value, source.data())) {
    throw Error(name + ": " + oiioMessage(in.geterror()));
  }

  std::vector<T> rgba(pixelCount * 4);
  expandToRgba(source.data(), channels, pixelCount, opaque, rgba.data());
  width = spec.width;
  height = spec.height;
  return rgba;
}

// The block-averaged read of TextureSize, for an image larger than maxSize.
Texture reducedTexture(OIIO::ImageInput& in, const std::string& name, int factor, bool srgb) {
  const OIIO::ImageSpec& spec = in.spec();
  if (uint64_t(spec.width) * uint64_t(spec.height) > kMaxPixels)
    throw Error(name + ": image too large (" + std::to_string(spec.width) + "x" +
                std::to_string(spec.height) + ")");
  const int channels = std::min(spec.nchannels, 4);
  const int outW = (spec.width + factor - 1) / factor, outH = (spec.height + factor - 1) / factor;
  std::array<float, 256> toLinear;  // the colour channels' decode, by byte value
  for (int v = 0; v < 256; ++v)
    toLinear[size_t(v)] = srgb ? srgbToLinear(float(v) / 255.0f) : float(v) / 255.0f;
  std::vector<uint8_t> strip(size_t(spec.width) * size_t(factor) * size_t(channels));
  std::vector<uint8_t> rgba(size_t(spec.width) * 4);
  std::vector<double> sums(size_t(outW) * 4);
  Texture texture;
  texture.name = name;
  texture.width = outW;
  texture.height = outH;
  texture.rgba8.resize(size_t(outW) * size_t(outH) * 4);
  for (int oy = 0; oy < outH; ++oy) {
    const int y0 = oy * factor, y1 = std::min(spec.height, y0 + factor);
    if (!in.read_scanlines(0, 0, y0, y1, 0, 0, channels, OIIO::TypeDesc::UINT8, strip.data()))
      throw Error(name + ": " + oiioMessage(in.geterror()));
    std::fill(sums.begin(), sums.end(), 0.0);
    for (int y = 0; y < y1 - y0; ++y) {
      expandToRgba(strip.data() + size_t(y) * size_t(spec.width) * size_t(channels), channels,
                   size_t(spec.width), uint8_t{255}, rgba.data());
      for (int x = 0; x < spec.width; ++x)
        for (int c = 0; c < 4; ++c) {
          const uint8_t v = rgba[size_t(x) * 4 + size_t(c)];
          sums[size_t(x / factor) * 4 + size_t(c)] +=
              c == 3 ? double(v) / 255.0 : double(toLinear[v]);
        }
    }
    for (int ox = 0; ox < outW; ++ox) {
      const int blockW = std::min(spec.width, (ox + 1) * factor) - ox * factor;
      const double count = double(blockW) * double(y1 - y0);
      for (int c = 0; c < 4; ++c) {
        float mean = float(sums[size_t(ox) * 4 + size_t(c)] / count);
        if (srgb && c != 3) mean = linearToSrgb(mean);
        texture.rgba8[(size_t(oy) * size_t(outW) + size_t(ox)) * 4 + size_t(c)] =
            static_cast<uint8_t>(std::lround(std::clamp(mean, 0.0f, 1.0f) * 255.0f));
      }
    }
  }
  return texture;
}

Texture toTexture(OIIO::ImageInput& in, const std::string& name, TextureSize size = {}) {
  const OIIO::ImageSpec& spec = in.spec();
  int factor = 1;
  while (size.maxSize > 0 && spec.depth == 1 && spec.nchannels > 0 &&
         std::max(spec.width, spec.height) / (2 * factor) >= size.maxSize)
    factor *= 2;
  if (factor > 1) return reducedTexture(in, name, factor, size.srgb);
  Texture texture;
  texture.name = name;
  texture.rgba8 = readRgba<uint8_t>(in, name, 255, texture.width, texture.height);
  return texture;
}

// PNG stores straight alpha, and so do glTF textures; by default OpenImageIO would premultiply
// on read and divide on write, which is lossy in 8 bits. Asking for unassociated alpha keeps the
// file's own values in both directions.
OIIO::ImageSpec straightAlphaConfig() {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}

void requireRegularFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": not a regular file");
}

// In-memory decoding cannot fall back to OIIO's "try every reader" (that only works on files in
// 2.4), so the format is recognised from its signature.
struct Signature {
  const char* format;  // OIIO plugin name
  std::string_view magic;
};
constexpr std::array kSignatures = {
    Signature{"png", std::string_view("\x89PNG\r\n\x1a\n", 8)},
    Signature{"jpeg", std::string_view("\xff\xd8\xff", 3)},
    Signature{"openexr", std::string_view("\x76\x2f\x31\x01", 4)},
    Signature{"tiff", std::string_view("II*\0", 4)},
    Signature{"tiff", std::string_view("MM\0*", 4)},
    Signature{"bmp", std::string_view("BM", 2)},
};

const char* detectFormat(std::span<const uint8_t> encoded) {
  for (const Signature& signature : kSignatures) {
    if (encoded.size() >= signature.magic.size() &&
        std::memcmp(encoded.data(), signature.magic.data(), signature.magic.size()) == 0) {
      return signature.format;
    }
  }
  return nullptr;
}

}  // namespace

void writeExr(const std::string& path, const ImageRgba32f& image) {
  validateSize(path, image.width, image.height, image.pixels.size());
  // Half floats keep ~3 significant digits up to 65504: plenty for radiance, half the size.
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::HALF);
  spec.attribute("compression", "zip");
  writeAtomically(path, "openexr", spec, OIIO::TypeDesc::FLOAT, image.pixels.data());
}

void writePng(const std::string& path, int width, int height, std::span<const uint8_t> rgba8) {
  validateSize(path, width, height, rgba8.size());
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha: see straightAlphaConfig()
  writeAtomically(path, "png", spec, OIIO::TypeDesc::UINT8, rgba8.data());
}

void writeAnimatedGif(const std::string& path, int width, int height,
                      std::span<const std::vector<uint8_t>> frames, int framesPerSecond) {
  if (frames.empty()) throw Error(path + ": an animation needs at least one frame");
  for (const std::vector<uint8_t>& frame : frames) validateSize(path, width, height, frame.size());
  TempFile temp(path);
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("gif");
  if (!out || !out->supports("multiimage"))
    throw Error(path + ": this OpenImageIO build cannot write animated GIF");
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("FramesPerSecond", OIIO::TypeRational,
                 std::array<int, 2>{framesPerSecond, 1}.data());
  spec.attribute("oiio:LoopCount", 0);  // forever
  const std::vector<OIIO::ImageSpec> specs(frames.size(), spec);
  if (!out->open(temp.path(), int(specs.size()), specs.data()))
    throw Error(path + ": " + oiioMessage(out->geterror()));
  for (size_t i = 0; i < frames.size(); ++i) {
    if (i > 0 && !out->open(temp.path(), specs[i], OIIO::ImageOutput::AppendSubimage))
      throw Error(path + ": " + oiioMessage(out->geterror()));
    if (!out->write_image(OIIO::TypeDesc::UINT8, frames[i].data()))
      throw Error(path + ": " + oiioMessage(out->geterror()));
  }
  if (!out->close()) throw Error(path + ": " + oiioMessage(out->geterror()));
  temp.commit();
}

ImageRgba32f readImage(const std::string& path) {
  requireRegularFile(path);
  const OIIO::ImageSpec config = straightAlphaConfig();
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path, &config);
  if (!in) throw Error(path + ": " + oiioMessage(OIIO::geterror()));
  ImageRgba32f image;
  image.pixels = readRgba<float>(*in, path, 1.0f, image.width, image.height);
  return image;
}

Texture decodeTexture(const std::string& name, std::span<const uint8_t> encoded, TextureSize size) {
  const char* format = detectFormat(encoded);
  if (format == nullptr) {
    throw Error(name + ": unrecognised image data (expected PNG, JPEG, OpenEXR, TIFF or BMP)");
  }
  // Declared before the ImageInput that reads through it, so it outlives the input's close().
  OIIO::Filesystem::IOMemReader reader(encoded.data(), encoded.size());
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create(format);
  if (!in) throw Error(name + ": " + oiioMessage(OIIO::geterror()));
  if (!in->supports("ioproxy")) {
    throw Error(name + ": this OpenImageIO build cannot decode " + format + " from memory");
  }
  OIIO::ImageSpec config = straightAlphaConfig();
  void* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  OIIO::ImageSpec spec;
  if (!in->open(name, spec, config)) throw Error(name + ": " + oiioMessage(in->geterror()));
  return toTexture(*in, name, size);
}

Texture readTexture(const std::string& path) {
  requireRegularFile(path);
  const OIIO::ImageSpec config = straightAlphaConfig();
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path, &config);
  if (!in) throw Error(path + ": " + oiioMessage(OIIO::geterror()));
  return toTexture(*in, path);
}

}  // namespace engine
