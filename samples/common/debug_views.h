// The sample programs' debug pictures (vsgl_render, vsgl_viewer), drawn on the CPU from what the
// public API hands back.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/image_io.h"
#include "shared/vsgl.h"

namespace samples {

// The VSGL lobes over a dimmed copy of `rgba8` (the tone-mapped frame): each lobe's mean as a
// circle of radius 2 sigma (sigma = sqrt(variance), projected; at least 2 pixels), cyan for
// diffuse lobes and orange for glossy ones, brighter for more power (log scale over three
// decades), and a tick from the mean along the lobe axis.
std::vector<uint8_t> drawVsglLobes(std::span<const uint8_t> rgba8, int width, int height,
                                   std::span<const gpu::Vsgl> vsgls, const glm::mat4& viewProj);

// A visibility image (R32F in [0, 1]) as grey RGBA8, sky and unlit pixels black.
std::vector<uint8_t> greyscale(std::span<const float> values);

// Adaptive shading's level map (FrameOutput::shadingLevels) over a grey copy of `rgba8`: pixels
// shaded at full rate red, light from level 1 yellow, 2 green, 3 blue; the sky left as it is.
std::vector<uint8_t> levelColours(std::span<const uint8_t> rgba8, std::span<const float> levels);

// Index of the VSGL with the largest total power (luminance weight of both lobes).
uint32_t brightestVsgl(std::span<const gpu::Vsgl> vsgls);

}  // namespace samples
