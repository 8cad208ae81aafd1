// Display transform for the PNG previews: exposure, then the Narkowicz fit of the ACES filmic
// curve, then the sRGB transfer function. The EXR outputs are never tone-mapped.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "engine/image_io.h"

namespace engine {

struct ToneMapSettings {
  // Exposure in stops. When empty, auto-exposure maps the log-average luminance of the lit
  // pixels (luminance > 0, and within 12 stops of the image's 99th percentile) to middle grey
  // 0.18 (Reinhard et al. 2002's "key").
  std::optional<float> exposureEv;
};

// The scale applied to linear radiance before the curve: 2^ev, or the auto-exposure factor.
float exposureScale(const ImageRgba32f& image, const ToneMapSettings& settings);

// ACES filmic fit (Narkowicz 2015) of one linear channel, output in [0, 1].
float acesFilmic(float x);

// Linear [0,1] -> sRGB-encoded [0,1] (IEC 61966-2-1).
float linearToSrgb(float x);

// sRGB-encoded [0,1] -> linear [0,1], the inverse of linearToSrgb.
float srgbToLinear(float x);

// Full display transform to 8-bit sRGB RGBA, alpha = 255. NaN/Inf pixels become magenta so
// they are impossible to miss.
std::vector<uint8_t> toneMap(const ImageRgba32f& image, const ToneMapSettings& settings);

}  // namespace engine
