#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine/tonemap.h"

namespace {

engine::ImageRgba32f constantImage(int width, int height, float r, float g, float b) {
  engine::ImageRgba32f image{width, height,
                             std::vector<float>(static_cast<size_t>(width * height) * 4)};
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    image.pixels[i + 0] = r;
    image.pixels[i + 1] = g;
    image.pixels[i + 2] = b;
    image.pixels[i + 3] = 1.0f;
  }
  return image;
}

TEST(ToneMap, AcesFilmicIsZeroAtZero) {
  EXPECT_EQ(engine::acesFilmic(0.0f), 0.0f);
}

TEST(ToneMap, AcesFilmicMatchesNarkowiczAtOne) {
  // 1 * (2.51 + 0.03) / (1 * (2.43 + 0.59) + 0.14) = 2.54 / 3.16
  EXPECT_NEAR(engine::acesFilmic(1.0f), 2.54f / 3.16f, 1e-6f);
}

TEST(ToneMap, AcesFilmicIsMonotonicAndSaturatesAtOne) {
  float previous = engine::acesFilmic(0.0f);
  for (float x = 0.01f; x < 100.0f; x *= 1.05f) {
    const float y = engine::acesFilmic(x);
    EXPECT_GE(y, previous) << "x = " << x;
    EXPECT_LE(y, 1.0f) << "x = " << x;
    previous = y;
  }
  EXPECT_GT(engine::acesFilmic(4.0f), 0.95f);
  EXPECT_EQ(engine::acesFilmic(1e3f), 1.0f);
  // x * x would overflow here without the input limit.
  EXPECT_EQ(engine::acesFilmic(std::numeric_limits<float>::max()), 1.0f);
  EXPECT_EQ(engine::acesFilmic(-1.0f), 0.0f);
}

TEST(ToneMap, LinearToSrgbEndpoints) {
  EXPECT_EQ(engine::linearToSrgb(0.0f), 0.0f);
  EXPECT_NEAR(engine::linearToSrgb(1.0f), 1.0f, 1e-6f);
}

TEST(ToneMap, LinearToSrgbIsContinuousAtKnee) {
  const float knee = 0.0031308f;
  const float below = engine::linearToSrgb(knee);
  const float above = engine::linearToSrgb(std::nextafter(knee, 1.0f));
  EXPECT_NEAR(below, 12.92f * knee, 1e-9f);
  EXPECT_LT(std::fabs(above - below), 1e-6f);
}

TEST(ToneMap, LinearToSrgbKnownValue) {
  // 1.055 * 0.5^(1/2.4) - 0.055
  EXPECT_NEAR(engine::linearToSrgb(0.5f), 0.735357f, 1e-6f);
}

TEST(ToneMap, ExposureEvIsPowerOfTwo) {
  const engine::ImageRgba32f image = constantImage(2, 2, 1.0f, 1.0f, 1.0f);
  EXPECT_EQ(engine::exposureScale(image, {1.0f}), 2.0f);
  EXPECT_EQ(engine::exposureScale(image, {-2.0f}), 0.25f);
  EXPECT_EQ(engine::exposureScale(image, {0.0f}), 1.0f);
}

TEST(ToneMap, AutoExposureMapsConstantLuminanceToMiddleGrey) {
  const float r = 0.5f;
  const float g = 2.0f;
  const float b = 0.25f;
  const engine::ImageRgba32f image = constantImage(8, 5, r, g, b);
  const double luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double mapped = engine::exposureScale(image, {}) * luminance;
  EXPECT_NEAR(mapped, 0.18, 0.18 * 1e-6);
}

TEST(ToneMap, AutoExposureIgnoresBlackAndNonFinitePixels) {
  engine::ImageRgba32f image = constantImage(4, 1, 3.0f, 3.0f, 3.0f);
  image.pixels[0] = image.pixels[1] = image.pixels[2] = 0.0f;
  image.pixels[4] = std::numeric_limits<float>::quiet_NaN();
  image.pixels[8] = std::numeric_limits<float>::infinity();
  // Only the last pixel (luminance 3) counts.
  EXPECT_NEAR(engine::exposureScale(image, {}), 0.06f, 0.06f * 1e-6f);
}

// A spot's pool of light in a dark room: 1 pixel in 5 at luminance 1, the rest 20 stops darker
// (faint indirect light). Exposed for the log-average of all five the pool would be scaled by
// 0.18 / 2^-16 and burn white; the near-black ones are left out, so the pool maps to middle grey.
TEST(ToneMap, AutoExposureLeavesOutTheNearBlack) {
  engine::ImageRgba32f image = constantImage(10, 10, 0x1p-20f, 0x1p-20f, 0x1p-20f);
  for (size_t p = 0; p < 100; p += 5)
    for (int c = 0; c < 3; ++c) image.pixels[4 * p + c] = 1.0f;
  EXPECT_NEAR(engine::exposureScale(image, {}), 0.18f, 0.18f * 1e-6f);
  // Within 12 stops of the bright end a dark pixel still counts: 2^-10 for the others gives the
  // log-average 2^-8 and the scale 0.18 x 2^8.
  for (size_t p = 0; p < 100; ++p)
    if (p % 5 != 0)
      for (int c = 0; c < 3; ++c) image.pixels[4 * p + c] = 0x1p-10f;
  EXPECT_NEAR(engine::exposureScale(image, {}), 0.18f * 256.0f, 0.18f * 256.0f * 1e-5f);
}

TEST(ToneMap, NonFinitePixelsBecomeMagenta) {
  engine::ImageRgba32f image = constantImage(3, 1, 0.2f, 0.2f, 0.2f);
  image.pixels[1] = std::numeric_limits<float>::quiet_NaN();
  image.pixels[6] = -std::numeric_limits<float>::infinity();
  const std::vector<uint8_t> out = engine::toneMap(image, {0.0f});
  ASSERT_EQ(out.size(), 12u);
  const std::vector<uint8_t> magenta = {255, 0, 255, 255};
  EXPECT_EQ(std::vector<uint8_t>(out.begin(), out.begin() + 4), magenta);
  EXPECT_EQ(std::vector<uint8_t>(out.begin() + 4, out.begin() + 8), magenta);
  EXPECT_NE(std::vector<uint8_t>(out.begin() + 8, out.end()), magenta);
}

TEST(ToneMap, AllZeroImageHasUnitScaleAndBlackOutput) {
  const engine::ImageRgba32f image = constantImage(4, 4, 0.0f, 0.0f, 0.0f);
  const float scale = engine::exposureScale(image, {});
  EXPECT_EQ(scale, 1.0f);
  const std::vector<uint8_t> out = engine::toneMap(image, {});
  for (size_t i = 0; i < out.size(); i += 4) {
    EXPECT_EQ(out[i + 0], 0);
    EXPECT_EQ(out[i + 1], 0);
    EXPECT_EQ(out[i + 2], 0);
    EXPECT_EQ(out[i + 3], 255);
  }
}

TEST(ToneMap, NegativeValuesClampToBlack) {
  const engine::ImageRgba32f image = constantImage(1, 1, -1.0f, 0.5f, -0.0f);
  const std::vector<uint8_t> out = engine::toneMap(image, {0.0f});
  EXPECT_EQ(out[0], 0);
  EXPECT_GT(out[1], 0);
  EXPECT_EQ(out[2], 0);
  EXPECT_EQ(out[3], 255);
}

TEST(ToneMap, ToneMapComposesExposureCurveAndEncoding) {
  engine::ImageRgba32f image = constantImage(2, 1, 0.05f, 0.3f, 1.5f);
  image.pixels[7] = 0.0f;  // source alpha never reaches the output
  const engine::ToneMapSettings settings{0.5f};
  const float scale = engine::exposureScale(image, settings);
  const std::vector<uint8_t> out = engine::toneMap(image, settings);
  for (size_t c = 0; c < 3; ++c) {
    const float expected =
        255.0f * engine::linearToSrgb(engine::acesFilmic(image.pixels[c] * scale));
    EXPECT_EQ(out[c], static_cast<uint8_t>(std::lround(expected)));
    EXPECT_EQ(out[4 + c], out[c]);
  }
  EXPECT_EQ(out[3], 255);
  EXPECT_EQ(out[7], 255);
}

}  // namespace
