// The converged reference of vsgl_environment: gi::envMonteCarloReference of every evaluated
// sphere pixel against the TRUE environment (the source equirect image read bilinearly, not the
// converted map), on all cores, cached in the output directory so that reruns skip it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <vector>

#include "engine/image_io.h"
#include "reference/env_fis_reference.h"

namespace environment {

struct ReferenceSettings {
  uint32_t glossyStrata = 256;   // glossyStrata^2 jittered lobe samples per pixel
  uint32_t diffuseStrata = 128;  // diffuseStrata^2 cosine samples per pixel
  unsigned threads = 0;          // 0: std::thread::hardware_concurrency()
};

struct ReferencePixel {
  glm::uvec2 pixel{0u};
  gi::EnvFisReceiver receiver;
};

struct Reference {
  std::vector<gi::EnvReferenceShading> shading;  // one per ReferencePixel, same order
  bool cached = false;                           // read from the cache file
  double seconds = 0.0;                          // wall time of the computation (0 if cached)
  std::filesystem::path file;                    // the cache file
};

// The reference of `pixels` against `equirect`, read from `cacheDir`/<stem>_<hash>.bin when a
// file there holds the same inputs (the hash covers the image's texels, every receiver, the
// settings and the estimator's seeds), otherwise computed and written there atomically (and
// older files of the same stem removed). Pixel i
// uses the seed 1 + pixel.y * 65536 + pixel.x, so neighbouring pixels' jitter is independent.
Reference loadOrComputeReference(const std::filesystem::path& cacheDir, const std::string& stem,
                                 const engine::ImageRgba32f& equirect,
                                 const std::vector<ReferencePixel>& pixels,
                                 const ReferenceSettings& settings);

}  // namespace environment
