#include "engine/tonemap.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <vector>

namespace engine {
namespace {

// Reinhard, Stark, Shirley, Ferwerda, "Photographic Tone Reproduction for Digital Images"
// (SIGGRAPH 2002): the log-average luminance is mapped to the "key" 0.18, middle grey.
constexpr double kMiddleGrey = 0.18;
// Auto-exposure leaves out pixels this many stops below the image's 99th-percentile luminance:
// the curve maps them to under 1/1000 of white once the rest is exposed (exposureScale).
constexpr float kDarkStops = 12.0f;

// Rec. ITU-R BT.709 luminance weights for linear RGB with the sRGB/Rec.709 primaries.
constexpr float kLuminanceR = 0.2126f;
constexpr float kLuminanceG = 0.7152f;
constexpr float kLuminanceB = 0.0722f;

// The Narkowicz fit reaches 1 at x ~= 7.24 and tends to 2.51/2.43 > 1, so every larger input
// clamps to 1; limiting x first keeps x * x finite for huge radiance.
constexpr float kAcesInputLimit = 64.0f;

// IEC 61966-2-1:1999 sRGB transfer function constants.
constexpr float kSrgbLinearKnee = 0.0031308f;
constexpr float kSrgbLinearSlope = 12.92f;
constexpr float kSrgbScale = 1.055f;
constexpr float kSrgbOffset = 0.055f;
constexpr float kSrgbExponent = 1.0f / 2.4f;

float luminance(float r, float g, float b) {
  return kLuminanceR * r + kLuminanceG * g + kLuminanceB * b;
}

uint8_t toUnorm8(float x) {
  return static_cast<uint8_t>(std::lround(x * 255.0f));
}

}  // namespace

float exposureScale(const ImageRgba32f& image, const ToneMapSettings& settings) {
  if (settings.exposureEv) return std::exp2(*settings.exposureEv);

  // Black (lum = 0) pixels are skipped because log(0) = -inf would drag the average to zero.
  std::vector<float> lit;
  for (size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
    const float lum = luminance(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]);
    if (std::isfinite(lum) && lum > 0.0f) lit.push_back(lum);
  }
  // Nothing lit: any scale gives black, so leave the radiance as it is.
  if (lit.empty()) return 1.0f;
  // So are pixels more than kDarkStops below the bright end (the 99th percentile): a frame that
  // is mostly near-black, a spot's pool of light in a dark room with faint indirect light around,
  // would otherwise be exposed for the near-black and burn the lit part white.
  std::vector<float> sorted = lit;
  const auto p99 = sorted.begin() + static_cast<std::ptrdiff_t>((sorted.size() - 1) * 99 / 100);
  std::nth_element(sorted.begin(), p99, sorted.end());
  const float darkest = *p99 * std::exp2(-kDarkStops);
  // The sum is in double so a large image does not lose the small terms.
  double logSum = 0.0;
  size_t count = 0;
  for (const float lum : lit)
    if (lum >= darkest) {
      logSum += std::log(static_cast<double>(lum));
      ++count;
    }
  return static_cast<float>(kMiddleGrey / std::exp(logSum / static_cast<double>(count)));
}

// Krzysztof Narkowicz, "ACES Filmic Tone Mapping Curve" (2015),
// https://knarkowicz.wordpress.com/2016/01/06/aces-filmic-tone-mapping-curve/ : a rational fit
// of the ACES RRT+ODT, with his constants a=2.51, b=0.03, c=2.43, d=0.59, e=0.14.
float acesFilmic(float x) {
  x = std::clamp(x, 0.0f, kAcesInputLimit);
  const float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(y, 0.0f, 1.0f);
}

// IEC 61966-2-1:1999 (sRGB), section 5.2: linear segment below the knee, 1/2.4 power above.
float srgbToLinear(float x) {
  return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  if (x <= kSrgbLinearKnee) return kSrgbLinearSlope * x;
  return kSrgbScale * std::pow(x, kSrgbExponent) - kSrgbOffset;
}

std::vector<uint8_t> toneMap(const ImageRgba32f& image, const ToneMapSettings& settings) {
  const size_t pixelCount = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  assert(image.pixels.size() == pixelCount * 4);
  const float scale = exposureScale(image, settings);

  std::vector<uint8_t> rgba8(pixelCount * 4);
  for (size_t i = 0; i < pixelCount; ++i) {
    const float* src = &image.pixels[i * 4];
    uint8_t* dst = &rgba8[i * 4];
    if (!std::isfinite(src[0]) || !std::isfinite(src[1]) || !std::isfinite(src[2])) {
      dst[0] = 255;
      dst[1] = 0;
      dst[2] = 255;
      dst[3] = 255;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      // Negative radiance (from filtering or noisy estimators) has no display meaning: clamp to 0.
      const float exposed = std::max(0.0f, src[c] * scale);
      dst[c] = toUnorm8(linearToSrgb(acesFilmic(exposed)));
    }
    dst[3] = 255;
  }
  return rgba8;
}

}  // namespace engine
