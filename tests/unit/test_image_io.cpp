#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "engine/error.h"
#include "engine/image_io.h"
#include "engine/tonemap.h"
#include "test_files.h"

namespace {

namespace fs = std::filesystem;

// tests/data/images was made once with OpenImageIO (ImageOutput, exact sample values):
//   grey8.png   3x2 uint8 Y  = {0, 1, 64, 128, 200, 255}
//   grey16.png  9x1 uint16 Y = {0, 128, 129, 385, 386, 32767, 32768, 32896, 65535}
//   solid.jpg   16x8 RGB (200, 100, 50), quality 95
const fs::path kImageData = fs::path(VSGL_TEST_DATA) / "images";

using test_files::readBytes;
using test_files::writeBytes;

// Deterministic bytes that deflate cannot shrink, so a PNG of them has a long IDAT to truncate.
std::vector<uint8_t> noiseRgba(int width, int height) {
  std::vector<uint8_t> bytes(static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  uint32_t state = 12345u;
  for (uint8_t& b : bytes) {
    state = state * 1664525u + 1013904223u;
    b = static_cast<uint8_t>(state >> 24);
  }
  return bytes;
}

// Runs `f`, which must throw engine::Error, and returns its message.
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const engine::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected engine::Error";
  return {};
}

void expectOneLineErrorNaming(const std::string& message, const std::string& name) {
  EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// Every test gets its own directory, so parallel ctest runs never share files.
class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("vsgl-image-io-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Names in the test directory that look like writer temp files ("<path>.tmp-<pid>").
  std::vector<std::string> tempLeftovers() const {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (name.find(".tmp-") != std::string::npos) names.push_back(name);
    }
    return names;
  }

  fs::path dir_;
};

TEST_F(ImageIoTest, ExrRoundTripKeepsHalfPrecision) {
  engine::ImageRgba32f image;
  image.width = 4;
  image.height = 3;
  // Geometric ramp over the range radiance outputs use: 1e-3 .. 6e4 (half max is 65504).
  const size_t count = static_cast<size_t>(image.width * image.height * 4);
  for (size_t i = 0; i < count; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(count - 1);
    image.pixels.push_back(static_cast<float>(1e-3 * std::pow(6e7, t)));
  }
  const std::string file = path("out.exr");
  engine::writeExr(file, image);
  EXPECT_TRUE(tempLeftovers().empty());

  const engine::ImageRgba32f back = engine::readImage(file);
  ASSERT_EQ(back.width, image.width);
  ASSERT_EQ(back.height, image.height);
  ASSERT_EQ(back.pixels.size(), image.pixels.size());
  for (size_t i = 0; i < count; ++i) {
    EXPECT_NEAR(back.pixels[i], image.pixels[i], 1e-3 * image.pixels[i]) << "value " << i;
  }
}

TEST_F(ImageIoTest, PngRoundTripIsExact) {
  const int width = 5;
  const int height = 3;
  const std::vector<uint8_t> rgba = noiseRgba(width, height);
  const std::string file = path("out.png");
  engine::writePng(file, width, height, rgba);
  EXPECT_TRUE(tempLeftovers().empty());

  const engine::Texture texture = engine::readTexture(file);
  EXPECT_EQ(texture.name, file);
  EXPECT_EQ(texture.width, width);
  EXPECT_EQ(texture.height, height);
  EXPECT_EQ(texture.rgba8, rgba);
}

// An animated GIF of two frames with a handful of colours (GIF's palette holds them exactly):
// the first frame reads back as written, written whole (no temp file left); frames of the wrong
// size, or none, give one-line errors and leave the previous file as it was.
TEST_F(ImageIoTest, AnimatedGifWritesItsFramesWhole) {
  const int width = 4, height = 2;
  std::vector<uint8_t> first(size_t(width) * height * 4), second(first.size());
  for (size_t i = 0; i < first.size(); i += 4) {
    const uint8_t v = static_cast<uint8_t>(60 * (i / 4 % 4));
    const uint8_t a[4] = {v, uint8_t(255 - v), 0, 255}, b[4] = {0, v, uint8_t(255 - v), 255};
    std::copy(a, a + 4, first.begin() + std::ptrdiff_t(i));
    std::copy(b, b + 4, second.begin() + std::ptrdiff_t(i));
  }
  const std::string file = path("anim.gif");
  const std::vector<std::vector<uint8_t>> frames = {first, second};
  engine::writeAnimatedGif(file, width, height, frames, 8);
  EXPECT_TRUE(tempLeftovers().empty());
  const engine::ImageRgba32f image = engine::readImage(file);
  ASSERT_EQ(image.width, width);
  ASSERT_EQ(image.height, height);
  for (size_t i = 0; i < first.size(); ++i)
    EXPECT_EQ(std::lround(image.pixels[i] * 255.0f), first[i]) << "byte " << i;

  const std::vector<uint8_t> before = readBytes(file);
  const std::vector<std::vector<uint8_t>> wrong = {first, std::vector<uint8_t>(4, 0)};
  expectOneLineErrorNaming(
      errorOf([&] { engine::writeAnimatedGif(file, width, height, wrong, 8); }), file);
  expectOneLineErrorNaming(errorOf([&] { engine::writeAnimatedGif(file, width, height, {}, 8); }),
                           file);
  EXPECT_EQ(readBytes(file), before);
  EXPECT_TRUE(tempLeftovers().empty());
}

TEST_F(ImageIoTest, DecodeTextureFromPngBytesInMemory) {
  const int width = 7;
  const int height = 4;
  const std::vector<uint8_t> rgba = noiseRgba(width, height);
  const std::string file = path("mem.png");
  engine::writePng(file, width, height, rgba);

  const std::vector<uint8_t> encoded = readBytes(file);
  const engine::Texture texture = engine::decodeTexture("scene.gltf#image0", encoded);
  EXPECT_EQ(texture.name, "scene.gltf#image0");
  EXPECT_EQ(texture.width, width);
  EXPECT_EQ(texture.height, height);
  EXPECT_EQ(texture.rgba8, rgba);
}

// A texture larger than TextureSize::maxSize is read in strips and block-averaged: 2050 x 1030
// to maxSize 1000 is f = 2 (f = 4 would leave 512 < 1000), 1025 x 515 texels, the last column
// and row averaging the 2 x 1 and 1 x 2 blocks they hold. Each texel against the mean of its
// block computed here from the full-size decode, in linear space for colour: within one 8-bit
// step (the two round the same mean once each). A smaller image is left as it is.
TEST_F(ImageIoTest, LargeTexturesAreBlockAveragedWhileRead) {
  const int width = 2050, height = 1030;
  const std::vector<uint8_t> rgba = noiseRgba(width, height);
  const std::string file = path("large.png");
  engine::writePng(file, width, height, rgba);
  const std::vector<uint8_t> encoded = readBytes(file);
  EXPECT_EQ(engine::decodeTexture("large.png", encoded, {4096, true}).rgba8, rgba);
  for (const bool srgb : {false, true}) {
    SCOPED_TRACE(srgb ? "sRGB" : "linear");
    const engine::Texture t = engine::decodeTexture("large.png", encoded, {1000, srgb});
    ASSERT_EQ(t.width, 1025);
    ASSERT_EQ(t.height, 515);
    int worst = 0;
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x)
        for (int c = 0; c < 4; ++c) {
          const bool colour = srgb && c != 3;
          double sum = 0.0;
          int n = 0;
          for (int yy = 2 * y; yy < std::min(height, 2 * y + 2); ++yy)
            for (int xx = 2 * x; xx < std::min(width, 2 * x + 2); ++xx, ++n) {
              const double v = rgba[(size_t(yy) * width + size_t(xx)) * 4 + size_t(c)] / 255.0;
              sum += colour ? engine::srgbToLinear(float(v)) : v;
            }
          const double mean = sum / n;
          const double expected = 255.0 * (colour ? engine::linearToSrgb(float(mean)) : mean);
          const int got = t.rgba8[(size_t(y) * t.width + size_t(x)) * 4 + size_t(c)];
          worst = std::max(worst, int(std::ceil(std::abs(got - expected) - 0.5)));
        }
    EXPECT_LE(worst, 1);
  }
}

TEST_F(ImageIoTest, DecodeTextureFromJpegBytesInMemory) {
  const engine::Texture texture =
      engine::decodeTexture("solid.jpg", readBytes(kImageData / "solid.jpg"));
  ASSERT_EQ(texture.width, 16);
  ASSERT_EQ(texture.height, 8);
  ASSERT_EQ(texture.rgba8.size(), size_t{16 * 8 * 4});
  // JPEG is lossy, but a flat colour survives within a couple of codes.
  for (size_t i = 0; i < texture.rgba8.size(); i += 4) {
    EXPECT_NEAR(texture.rgba8[i + 0], 200, 2);
    EXPECT_NEAR(texture.rgba8[i + 1], 100, 2);
    EXPECT_NEAR(texture.rgba8[i + 2], 50, 2);
    EXPECT_EQ(texture.rgba8[i + 3], 255);
  }
}

TEST_F(ImageIoTest, DecodeTextureFromExrBytesConvertsTo8Bit) {
  engine::ImageRgba32f image{2, 1, {0.0f, 0.25f, 1.0f, 1.0f, 0.5f, 0.5f, 0.5f, 0.0f}};
  const std::string file = path("mem.exr");
  engine::writeExr(file, image);
  const engine::Texture texture = engine::decodeTexture("mem.exr", readBytes(file));
  // 0.25 * 255 = 63.75 and 0.5 * 255 = 127.5 round to nearest.
  EXPECT_EQ(texture.rgba8, (std::vector<uint8_t>{0, 64, 255, 255, 128, 128, 128, 0}));
}

TEST_F(ImageIoTest, GreyPngReplicatesRgbWithOpaqueAlpha) {
  const std::vector<uint8_t> expected = {
      0,   0,   0,   255, 1,   1,   1,   255, 64,  64,  64,  255,
      128, 128, 128, 255, 200, 200, 200, 255, 255, 255, 255, 255,
  };
  const fs::path file = kImageData / "grey8.png";
  const engine::Texture fromFile = engine::readTexture(file.string());
  EXPECT_EQ(fromFile.width, 3);
  EXPECT_EQ(fromFile.height, 2);
  EXPECT_EQ(fromFile.rgba8, expected);

  const engine::Texture fromMemory = engine::decodeTexture("grey8.png", readBytes(file));
  EXPECT_EQ(fromMemory.rgba8, expected);
}

TEST_F(ImageIoTest, ReadImageOfGreyPngGivesFloatRgbaWithUnitAlpha) {
  const engine::ImageRgba32f image = engine::readImage((kImageData / "grey8.png").string());
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  const float grey[] = {0, 1, 64, 128, 200, 255};
  for (size_t i = 0; i < 6; ++i) {
    for (size_t c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(image.pixels[i * 4 + c], grey[i] / 255.0f);
    EXPECT_EQ(image.pixels[i * 4 + 3], 1.0f);
  }
}

TEST_F(ImageIoTest, SixteenBitPngRoundsTo8Bit) {
  const engine::Texture texture = engine::readTexture((kImageData / "grey16.png").string());
  ASSERT_EQ(texture.width, 9);
  ASSERT_EQ(texture.height, 1);
  // round(v * 255 / 65535): 128 -> 0.498, 129 -> 0.502, 385 -> 1.498, 386 -> 1.502, ...
  const uint8_t expected[] = {0, 0, 1, 1, 2, 127, 128, 128, 255};
  for (size_t i = 0; i < 9; ++i) {
    EXPECT_EQ(texture.rgba8[i * 4 + 0], expected[i]) << "pixel " << i;
    EXPECT_EQ(texture.rgba8[i * 4 + 1], expected[i]) << "pixel " << i;
    EXPECT_EQ(texture.rgba8[i * 4 + 2], expected[i]) << "pixel " << i;
    EXPECT_EQ(texture.rgba8[i * 4 + 3], 255) << "pixel " << i;
  }
}

TEST_F(ImageIoTest, WriteIntoMissingDirectoryThrowsOneLineError) {
  const std::string png = path("missing/out.png");
  expectOneLineErrorNaming(errorOf([&] { engine::writePng(png, 1, 1, noiseRgba(1, 1)); }), png);

  const std::string exr = path("missing/out.exr");
  const engine::ImageRgba32f image{1, 1, {1.0f, 1.0f, 1.0f, 1.0f}};
  expectOneLineErrorNaming(errorOf([&] { engine::writeExr(exr, image); }), exr);
  EXPECT_FALSE(fs::exists(path("missing")));
}

TEST_F(ImageIoTest, WriteUnderRegularFileThrowsOneLineError) {
  writeBytes(path("plain"), {'x'});
  const std::string png = path("plain/out.png");
  expectOneLineErrorNaming(errorOf([&] { engine::writePng(png, 1, 1, noiseRgba(1, 1)); }), png);
}

TEST_F(ImageIoTest, InvalidInputLeavesExistingFileUntouched) {
  const std::string png = path("out.png");
  engine::writePng(png, 4, 4, noiseRgba(4, 4));
  const std::vector<uint8_t> good = readBytes(png);

  expectOneLineErrorNaming(errorOf([&] { engine::writePng(png, 0, 4, {}); }), png);
  expectOneLineErrorNaming(errorOf([&] { engine::writePng(png, 4, 4, noiseRgba(4, 3)); }), png);
  EXPECT_EQ(readBytes(png), good);

  const std::string exr = path("out.exr");
  engine::writeExr(exr, {2, 2, std::vector<float>(16, 0.5f)});
  const std::vector<uint8_t> goodExr = readBytes(exr);
  const engine::ImageRgba32f shortImage{2, 2, std::vector<float>(15, 0.5f)};
  expectOneLineErrorNaming(errorOf([&] { engine::writeExr(exr, shortImage); }), exr);
  expectOneLineErrorNaming(errorOf([&] { engine::writeExr(exr, {2, -2, {}}); }), exr);
  EXPECT_EQ(readBytes(exr), goodExr);
  EXPECT_TRUE(tempLeftovers().empty());
}

TEST_F(ImageIoTest, FailedWriteLeavesExistingFileByteIdentical) {
  const std::string png = path("out.png");
  engine::writePng(png, 4, 4, noiseRgba(4, 4));
  const std::vector<uint8_t> good = readBytes(png);

  // Occupying the temp name with a directory makes OpenImageIO's open() fail.
  const fs::path blocker = png + ".tmp-" + std::to_string(::getpid());
  fs::create_directory(blocker);
  writeBytes(blocker / "keep", {'k'});
  expectOneLineErrorNaming(errorOf([&] { engine::writePng(png, 2, 2, noiseRgba(2, 2)); }), png);
  EXPECT_EQ(readBytes(png), good);
  // The writer never deletes what it did not create.
  EXPECT_TRUE(fs::exists(blocker / "keep"));
}

TEST_F(ImageIoTest, FailedRenameRemovesTempFile) {
  // Encoding succeeds, but a file cannot be renamed over a directory.
  const std::string target = path("taken");
  fs::create_directory(target);
  expectOneLineErrorNaming(errorOf([&] { engine::writePng(target, 2, 2, noiseRgba(2, 2)); }),
                           target);
  const engine::ImageRgba32f image{1, 1, {1.0f, 1.0f, 1.0f, 1.0f}};
  expectOneLineErrorNaming(errorOf([&] { engine::writeExr(target, image); }), target);
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_TRUE(tempLeftovers().empty());
}

TEST_F(ImageIoTest, ReadMissingFileThrowsOneLineError) {
  const std::string file = path("absent.png");
  expectOneLineErrorNaming(errorOf([&] { engine::readTexture(file); }), file);
  expectOneLineErrorNaming(errorOf([&] { engine::readImage(file); }), file);
}

TEST_F(ImageIoTest, ReadTruncatedPngThrowsOneLineError) {
  const std::string whole = path("whole.png");
  engine::writePng(whole, 64, 64, noiseRgba(64, 64));
  std::vector<uint8_t> bytes = readBytes(whole);
  bytes.resize(bytes.size() / 2);
  const std::string file = path("truncated.png");
  writeBytes(file, bytes);

  expectOneLineErrorNaming(errorOf([&] { engine::readTexture(file); }), file);
  expectOneLineErrorNaming(errorOf([&] { engine::decodeTexture("truncated", bytes); }),
                           "truncated");
}

TEST_F(ImageIoTest, ReadTextFileNamedPngThrowsOneLineError) {
  const std::string text = "this is not an image\nsecond line\n";
  const std::vector<uint8_t> bytes(text.begin(), text.end());
  const std::string file = path("text.png");
  writeBytes(file, bytes);

  expectOneLineErrorNaming(errorOf([&] { engine::readTexture(file); }), file);
  expectOneLineErrorNaming(errorOf([&] { engine::decodeTexture("text.png", bytes); }), "text.png");
}

TEST_F(ImageIoTest, ReadEmptyFileThrowsOneLineError) {
  const std::string file = path("empty.png");
  writeBytes(file, {});
  expectOneLineErrorNaming(errorOf([&] { engine::readTexture(file); }), file);
  expectOneLineErrorNaming(errorOf([&] { engine::decodeTexture("empty", {}); }), "empty");
}

}  // namespace
