#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "engine/error.h"
#include "engine/gbuffer_reference.h"
#include "engine/image_io.h"
#include "engine/image_metrics.h"

namespace {

using engine::PixelClass;
using glm::dvec3;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The ends and middle of the published viridis map as 8-bit sRGB: #440154, #21918c, #fde725.
constexpr std::array<uint8_t, 4> kViridisFirst{68, 1, 84, 255};
constexpr std::array<uint8_t, 4> kViridisMiddle{33, 145, 140, 255};
constexpr std::array<uint8_t, 4> kViridisLast{253, 231, 37, 255};
constexpr std::array<uint8_t, 4> kMagenta{255, 0, 255, 255};

std::array<uint8_t, 4> pixelAt(const std::vector<uint8_t>& rgba, size_t i) {
  return {rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2], rgba[i * 4 + 3]};
}

// The message of the engine::Error `f` throws, or "" when it throws none.
template <typename F>
std::string errorMessage(F&& f) {
  try {
    f();
  } catch (const engine::Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImageMetrics, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  const std::vector<dvec3> image{{0.1, 0.2, 0.3}, {1.0, 2.0, 3.0}, {0.0, 0.0, 0.0}, {5, 6, 7}};
  const engine::ErrorMetrics m = engine::compareImages(image, image);
  EXPECT_EQ(m.pixels, 4u);
  EXPECT_EQ(m.nonFinite, 0u);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.relativeMse, 0.0);
  EXPECT_EQ(m.psnr, kInf);
  // (0.1 + 0.2 + 0.3 + 1 + 2 + 3 + 0 + 0 + 0 + 5 + 6 + 7) / 12 = 24.6 / 12
  EXPECT_NEAR(m.referenceMean, 24.6 / 12.0, 1e-12);
}

TEST(ImageMetrics, HandComputedTwoByTwo) {
  const std::vector<dvec3> reference{{1, 0, 0}, {0, 1, 0}, {0, 0, 2}, {1, 1, 1}};
  const std::vector<dvec3> test{{1.5, 0, 0}, {0, 1, 0.1}, {0, 0, 2}, {1, 1, 0}};
  // Squared differences, the only non-zero channels:
  //   pixel 0 red:  (1.5 - 1)^2 = 0.25, relative 0.25 / (1 + 0.01)
  //   pixel 1 blue: (0.1 - 0)^2 = 0.01, relative 0.01 / (0 + 0.01) = 1
  //   pixel 3 blue: (0 - 1)^2   = 1,    relative 1 / (1 + 0.01)
  // mse = 1.26 / 12 = 0.105, rmse = sqrt(0.105) = 0.324037...
  // relMSE = (0.25 / 1.01 + 1 + 1 / 1.01) / 12 = 0.186468...
  // peak = 2 (pixel 2 blue), psnr = 10 log10(4 / 0.105) = 15.8087... dB
  // referenceMean = (1 + 1 + 2 + 3) / 12 = 7 / 12
  const engine::ErrorMetrics m = engine::compareImages(test, reference);
  EXPECT_EQ(m.pixels, 4u);
  EXPECT_NEAR(m.rmse, std::sqrt(0.105), 1e-12);
  EXPECT_NEAR(m.rmse, 0.324037, 1e-6);
  EXPECT_NEAR(m.relativeMse, (0.25 / 1.01 + 1.0 + 1.0 / 1.01) / 12.0, 1e-12);
  EXPECT_NEAR(m.relativeMse, 0.186469, 1e-6);
  EXPECT_NEAR(m.psnr, 10.0 * std::log10(4.0 / 0.105), 1e-9);
  EXPECT_NEAR(m.psnr, 15.8087, 1e-4);
  EXPECT_NEAR(m.referenceMean, 7.0 / 12.0, 1e-12);
}

TEST(ImageMetrics, ClassSplitCountsEachClassAndIgnoresExcluded) {
  const std::vector<PixelClass> classes{PixelClass::Excluded, PixelClass::Diffuse,
                                        PixelClass::Glossy,   PixelClass::Diffuse,
                                        PixelClass::Glossy,   PixelClass::Excluded};
  const std::vector<dvec3> reference{{0, 0, 0}, {1, 1, 1}, {2, 2, 2},
                                     {1, 1, 1}, {2, 2, 2}, {0, 0, 0}};
  // Excluded pixels are wildly wrong (one even NaN): none of it may show.
  const std::vector<dvec3> test{{100, 100, 100}, {1.1, 1.1, 1.1}, {1, 1, 1},
                                {1, 1, 1},       {2, 2, 2},       {kNaN, 0, 0}};
  // Diffuse: 3 channels of 0.1^2 over 6 values -> mse 0.005, peak 1, mean 1.
  // Glossy:  3 channels of 1^2 over 6 values   -> mse 0.5,   peak 2, mean 2.
  // All:     (0.03 + 3) / 12 = 0.2525,          peak 2, mean 1.5.
  const engine::SplitMetrics s = engine::compareImagesSplit(test, reference, classes);
  EXPECT_EQ(s.all.pixels, 4u);
  EXPECT_EQ(s.diffuse.pixels, 2u);
  EXPECT_EQ(s.glossy.pixels, 2u);
  EXPECT_EQ(s.all.nonFinite, 0u);
  EXPECT_NEAR(s.diffuse.rmse, std::sqrt(0.005), 1e-12);
  EXPECT_NEAR(s.glossy.rmse, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(s.all.rmse, std::sqrt(0.2525), 1e-12);
  EXPECT_NEAR(s.diffuse.psnr, 10.0 * std::log10(1.0 / 0.005), 1e-9);
  EXPECT_NEAR(s.glossy.psnr, 10.0 * std::log10(4.0 / 0.5), 1e-9);
  EXPECT_NEAR(s.all.referenceMean, 1.5, 1e-12);
  // Glossy relMSE: 1 / (4 + 0.01) on half the values.
  EXPECT_NEAR(s.glossy.relativeMse, 0.5 / 4.01, 1e-12);

  // A mask with only excluded pixels left leaves nothing: every metric 0.
  const engine::ErrorMetrics none =
      engine::compareImages(test, reference, classes, PixelClass::Excluded);
  EXPECT_EQ(none.pixels, 0u);
  EXPECT_EQ(none.rmse, 0.0);
  EXPECT_EQ(none.psnr, 0.0);
}

TEST(ImageMetrics, NonFiniteTestPixelsAreCountedNotAveraged) {
  const std::vector<dvec3> reference(4, dvec3(1.0));
  const std::vector<dvec3> test{{1, kNaN, 1}, {kInf, 1, 1}, {1, 1, 1}, {2, 2, 2}};
  // Finite pixels 2 and 3: 3 channels of 1^2 over 6 values -> mse 0.5.
  const engine::ErrorMetrics m = engine::compareImages(test, reference);
  EXPECT_EQ(m.nonFinite, 2u);
  EXPECT_EQ(m.pixels, 2u);
  EXPECT_NEAR(m.rmse, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m.relativeMse, 0.5 / 1.01, 1e-12);
  EXPECT_NEAR(m.psnr, 10.0 * std::log10(1.0 / 0.5), 1e-9);
  EXPECT_NEAR(m.referenceMean, 1.0, 1e-12);
}

TEST(ImageMetrics, AllTestPixelsNonFiniteGivesZeroMetrics) {
  const std::vector<dvec3> reference(2, dvec3(1.0));
  const std::vector<dvec3> test(2, dvec3(kNaN));
  const engine::ErrorMetrics m = engine::compareImages(test, reference);
  EXPECT_EQ(m.nonFinite, 2u);
  EXPECT_EQ(m.pixels, 0u);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.relativeMse, 0.0);
  EXPECT_EQ(m.psnr, 0.0);
  EXPECT_EQ(m.referenceMean, 0.0);
}

TEST(ImageMetrics, NonFiniteReferenceThrows) {
  const std::vector<dvec3> reference{{1, 1, 1}, {1, kNaN, 1}};
  const std::vector<dvec3> test(2, dvec3(1.0));
  const std::string message = errorMessage([&] { engine::compareImages(test, reference); });
  EXPECT_NE(message.find("reference pixel 1"), std::string::npos) << message;
}

TEST(ImageMetrics, MismatchedSizesThrowNamingBothSizes) {
  const std::vector<dvec3> four(4, dvec3(1.0));
  const std::vector<dvec3> three(3, dvec3(1.0));
  const std::vector<PixelClass> threeClasses(3, PixelClass::Diffuse);

  std::string message = errorMessage([&] { engine::compareImages(four, three); });
  EXPECT_NE(message.find("test has 4"), std::string::npos) << message;
  EXPECT_NE(message.find("reference has 3"), std::string::npos) << message;

  message = errorMessage([&] { engine::compareImages(four, four, threeClasses); });
  EXPECT_NE(message.find("3 entries"), std::string::npos) << message;
  EXPECT_NE(message.find("4 pixels"), std::string::npos) << message;

  EXPECT_THROW(engine::compareImagesSplit(four, four, {}), engine::Error);
  EXPECT_THROW(engine::compareImages(four, four, {}, PixelClass::Glossy), engine::Error);
  EXPECT_THROW(engine::falseColourError(four, three, 1.0), engine::Error);
  EXPECT_THROW(engine::percentileAbsError(four, three, 0.5), engine::Error);
}

TEST(ImageMetrics, PercentileOfLuminanceErrorIsNearestRank) {
  // Red-only differences: luminance error = 0.2126 * k for k = 1..4, plus a NaN pixel that is
  // left out.
  const std::vector<dvec3> reference(5, dvec3(0.0));
  const std::vector<dvec3> test{{3, 0, 0}, {1, 0, 0}, {kNaN, 0, 0}, {4, 0, 0}, {2, 0, 0}};
  EXPECT_NEAR(engine::percentileAbsError(test, reference, 0.0), 0.2126, 1e-12);
  // ceil(0.5 * 4) = rank 2.
  EXPECT_NEAR(engine::percentileAbsError(test, reference, 0.5), 2 * 0.2126, 1e-12);
  // ceil(0.99 * 4) = rank 4.
  EXPECT_NEAR(engine::percentileAbsError(test, reference, 0.99), 4 * 0.2126, 1e-12);
  EXPECT_NEAR(engine::percentileAbsError(test, reference, 1.0), 4 * 0.2126, 1e-12);
  EXPECT_THROW(engine::percentileAbsError(test, reference, 1.5), engine::Error);
}

TEST(PixelClassification, BackgroundAndRoughnessThreshold) {
  engine::GBufferSample background;  // depth 1: nothing visible
  background.roughness = 0.1;
  EXPECT_EQ(engine::classifyPixel(background), PixelClass::Excluded);

  engine::GBufferSample surface;
  surface.depth = 0.5f;
  surface.roughness = 0.5;
  EXPECT_EQ(engine::classifyPixel(surface), PixelClass::Glossy);
  surface.roughness = 0.51;
  EXPECT_EQ(engine::classifyPixel(surface), PixelClass::Diffuse);
  surface.roughness = 0.0;
  EXPECT_EQ(engine::classifyPixel(surface), PixelClass::Glossy);
}

TEST(PixelClassification, ClassifiesEveryGBufferTexelInOrder) {
  engine::GBufferData g;
  g.width = 3;
  g.height = 1;
  g.samples.resize(3);
  g.samples[1].depth = 0.3f;
  g.samples[1].roughness = 0.9;
  g.samples[2].depth = 0.7f;
  g.samples[2].roughness = 0.2;
  const std::vector<PixelClass> expected{PixelClass::Excluded, PixelClass::Diffuse,
                                         PixelClass::Glossy};
  EXPECT_EQ(engine::classifyPixels(g), expected);
}

TEST(FalseColour, MapsErrorOntoViridisAndNonFiniteOntoMagenta) {
  // Grey pixels, so the luminance difference is the grey difference (weights sum to 1).
  const std::vector<dvec3> reference{dvec3(1.0), dvec3(1.0), dvec3(1.0),
                                     dvec3(1.0), dvec3(1.0), dvec3(1.0)};
  const std::vector<dvec3> test{dvec3(1.0), dvec3(3.0),   dvec3(11.0),
                                dvec3(2.0), {1, kNaN, 1}, dvec3(-kInf)};
  const std::vector<uint8_t> rgba = engine::falseColourError(test, reference, 2.0);
  ASSERT_EQ(rgba.size(), 6u * 4u);
  EXPECT_EQ(pixelAt(rgba, 0), kViridisFirst);  // e = 0
  EXPECT_EQ(pixelAt(rgba, 1), kViridisLast);   // e = maxError
  EXPECT_EQ(pixelAt(rgba, 2), kViridisLast);   // e = 5 maxError, clamped
  EXPECT_EQ(pixelAt(rgba, 4), kMagenta);
  EXPECT_EQ(pixelAt(rgba, 5), kMagenta);
  // e = maxError / 2: the middle of the map, within one step of rounding the interpolation.
  for (size_t c = 0; c < 4; ++c) {
    EXPECT_NEAR(pixelAt(rgba, 3)[c], kViridisMiddle[c], 1) << "channel " << c;
  }
}

TEST(FalseColour, ZeroMaxErrorDrawsAnyErrorAsTheLastColour) {
  const std::vector<dvec3> reference{dvec3(1.0), dvec3(1.0)};
  const std::vector<dvec3> test{dvec3(1.0), dvec3(1.5)};
  const std::vector<uint8_t> rgba = engine::falseColourError(test, reference, 0.0);
  EXPECT_EQ(pixelAt(rgba, 0), kViridisFirst);
  EXPECT_EQ(pixelAt(rgba, 1), kViridisLast);
  EXPECT_THROW(engine::falseColourError(test, reference, -1.0), engine::Error);
}

TEST(FalseColour, WritesThePictureAsPng) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("vsgl-false-colour-" + std::to_string(::getpid()) + ".png");
  const std::vector<dvec3> reference(6, dvec3(0.0));
  const std::vector<dvec3> test{dvec3(0.0), dvec3(1.0),  dvec3(0.0),
                                dvec3(0.0), dvec3(kNaN), dvec3(1.0)};
  engine::writeFalseColourError(path.string(), 3, 2, test, reference, 1.0);
  const engine::ImageRgba32f image = engine::readImage(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  const std::vector<uint8_t> expected = engine::falseColourError(test, reference, 1.0);
  ASSERT_EQ(image.pixels.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(std::lround(image.pixels[i] * 255.0f), expected[i]) << "byte " << i;
  }
  EXPECT_THROW(engine::writeFalseColourError(path.string(), 2, 2, test, reference, 1.0),
               engine::Error);
}

// The flicker figure (docs/flicker.md): 0 exactly for a static pair, 0 when the method moves
// exactly as the reference does (a constant bias included), and the RMS of the change it adds
// over the reference's mean otherwise; a non-finite pixel is refused.
TEST(TemporalError, StaticIsZeroSharedMotionCancelsAndAddedChangeCounts) {
  const std::vector<dvec3> r0{dvec3(1.0), dvec3(2.0), dvec3(3.0), dvec3(2.0)};
  const std::vector<dvec3> r1{dvec3(2.0), dvec3(1.0), dvec3(3.0), dvec3(2.0)};
  std::vector<dvec3> i0(r0), i1(r1);
  for (auto& v : i0) v += dvec3(0.5);  // a bias, the same in both frames
  for (auto& v : i1) v += dvec3(0.5);
  EXPECT_EQ(engine::temporalError(i0, i0, r0, r0), 0.0);
  EXPECT_EQ(engine::temporalError(i0, i1, r0, r1), 0.0);
  std::vector<dvec3> flicker(i1);
  flicker[2] += dvec3(0.8, 0.0, 0.0);  // one channel of one pixel jumps by 0.8
  // RMS over 4 pixels x 3 channels: sqrt(0.64 / 12); reference mean 2.
  EXPECT_NEAR(engine::temporalError(i0, flicker, r0, r1), std::sqrt(0.64 / 12.0) / 2.0, 1e-15);
  const std::vector<dvec3> black(4, dvec3(0.0));
  EXPECT_NEAR(
      engine::temporalError(black, flicker, black, black),
      std::sqrt((3 * 1.5 * 1.5 + 3 * 2.5 * 2.5 + (4.3 * 4.3 + 2 * 3.5 * 3.5) + 3 * 2.5 * 2.5) /
                12.0),
      1e-12);
  // A mask leaves pixels out: only pixel 2 counted, sqrt(0.64 / 3) over its reference mean 3.
  const std::vector<uint8_t> only2{0, 0, 1, 0};
  EXPECT_NEAR(engine::temporalError(i0, flicker, r0, r1, only2), std::sqrt(0.64 / 3.0) / 3.0,
              1e-15);
  std::vector<dvec3> bad(i1);
  bad[1].y = kNaN;
  EXPECT_THROW(engine::temporalError(i0, bad, r0, r1), engine::Error);
}

// Block means: exact means of the valid pixels of each whole block; a block with fewer than half
// of its pixels valid is invalid (mean 0); the partial right column of blocks is dropped.
TEST(BlockMeans, MeansOfValidPixelsAndHalfRule) {
  // 5 x 2 image, 2 x 2 blocks: two whole blocks, the fifth column dropped.
  std::vector<dvec3> image(10);
  for (size_t i = 0; i < image.size(); ++i) image[i] = dvec3(double(i));
  std::vector<uint8_t> valid(10, 1);
  valid[2] = 0;                        // block 1 keeps 3 of 4: pixels 3, 7, 8
  valid[0] = valid[1] = valid[5] = 0;  // block 0 keeps 1 of 4: invalid
  const engine::BlockMeans b = engine::blockMeans(image, 5, 2, 2, valid);
  ASSERT_EQ(b.width, 2u);
  ASSERT_EQ(b.height, 1u);
  EXPECT_EQ(b.valid, (std::vector<uint8_t>{0, 1}));
  EXPECT_EQ(b.means[0], dvec3(0.0));
  EXPECT_EQ(b.means[1], dvec3((3.0 + 7.0 + 8.0) / 3.0));
  const engine::BlockMeans all = engine::blockMeans(image, 5, 2, 2);
  EXPECT_EQ(all.means[0], dvec3((0.0 + 1.0 + 5.0 + 6.0) / 4.0));
  EXPECT_THROW(engine::blockMeans(image, 4, 2, 2), engine::Error);
  EXPECT_THROW(engine::blockMeans(image, 5, 2, 0), engine::Error);
}

}  // namespace
