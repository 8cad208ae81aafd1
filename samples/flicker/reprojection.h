// Camera-motion compensation for the flicker figure (docs/flicker.md): where each pixel's surface
// point of frame t was seen in frame t-1, so that a moving camera compares a surface with itself
// instead of with whatever slid under the pixel. Pixels that were hidden, outside the previous
// frame or sky are left out.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "engine/gbuffer_reference.h"
#include "engine/view.h"

namespace flicker {

struct Reprojection {
  std::vector<std::array<uint32_t, 4>> taps;   // previous pixels, bilinear neighbours
  std::vector<std::array<double, 4>> weights;  // summing to 1 over valid taps
  std::vector<uint8_t> valid;                  // 0: the pixel is left out
};

// Identity (one tap of weight 1, exactly) when the two views are equal. Otherwise each pixel's
// point, rebuilt from its depth, is projected into the previous view and read bilinearly from
// the previous pixels whose own points lie within 1 % of the camera distance of it (the rest of
// the four taps are dropped and the weights renormalised; none left = left out).
Reprojection reproject(const engine::GBufferData& previous, const engine::View& previousView,
                       const engine::GBufferData& current, const engine::View& currentView);

// `image` (of the previous frame) read at every current pixel through `r`; 0 where not valid.
std::vector<glm::dvec3> resample(const std::vector<glm::dvec3>& image, const Reprojection& r);

}  // namespace flicker
