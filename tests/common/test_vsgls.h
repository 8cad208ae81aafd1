// VSGL records for GPU tests, built the way the generation pass fills them.
#pragma once

#include <glm/glm.hpp>

#include "shared/vsgl.h"

namespace testing_gpu {

// One lobe: mean and variance, unit axis and sharpness, RGB power (power.a = its luminance, the
// Rec. 709 weight the passes store).
inline gpu::VsglLobe vsglLobe(glm::vec3 mean, float variance, glm::vec3 axis, float sharpness,
                              glm::vec3 power) {
  gpu::VsglLobe l{};
  l.meanVariance = glm::vec4(mean, variance);
  l.axisSharpness = glm::vec4(glm::normalize(axis), sharpness);
  l.power = glm::vec4(power, 0.2126f * power.r + 0.7152f * power.g + 0.0722f * power.b);
  return l;
}

}  // namespace testing_gpu
