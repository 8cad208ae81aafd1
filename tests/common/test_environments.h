// Environments for the environment-lighting tests: a smooth radiance function of direction, and
// any such function sampled into an equirectangular image (the conventions of
// gi/src/reference/env_paraboloid.h), as a host would hand it over.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>

#include "engine/image_io.h"
#include "reference/env_paraboloid.h"

namespace testing_common {

// A sky gradient, a broad warm lobe and a dim ground lobe: smooth, no texel-scale detail.
inline glm::dvec3 smoothEnvironment(glm::dvec3 w) {
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.5, 0.7, 0.4));
  return glm::dvec3(0.35, 0.45, 0.6) * (0.7 + 0.3 * w.y) +
         glm::dvec3(3.0, 2.4, 1.6) * std::exp(6.0 * (glm::dot(w, sun) - 1.0)) +
         glm::dvec3(0.25, 0.2, 0.1) * std::exp(3.0 * (-w.y - 1.0));
}

// `radiance` at the texel centres of a width x width / 2 equirectangular image (alpha 1).
inline engine::ImageRgba32f equirectOf(uint32_t width,
                                       const std::function<glm::dvec3(glm::dvec3)>& radiance) {
  const uint32_t height = width / 2;
  engine::ImageRgba32f image{int(width), int(height), {}};
  image.pixels.resize(size_t{width} * height * 4);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const glm::dvec3 l =
          radiance(gi::equirectToDirection({(x + 0.5) / width, (y + 0.5) / height}));
      float* p = &image.pixels[(size_t{y} * width + x) * 4];
      p[0] = float(l.x), p[1] = float(l.y), p[2] = float(l.z), p[3] = 1.0f;
    }
  return image;
}

}  // namespace testing_common
