// CPU twin of the compute rasterizer (raster_setup.comp + raster_triangles.comp): the same
// clipping, fixed-point snapping, fill rule and depth interpolation, evaluated in the same
// order without FMA contraction, so it predicts the GPU visibility buffer bit for bit on
// IEEE-conformant devices. Naive on purpose: every triangle tests every pixel of its box.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "engine/rasterizer.h"
#include "engine/scene.h"

namespace engine {

struct ReferenceRaster {
  std::vector<uint64_t> visibility;  // as the GPU: (depth bits << 32) | triangle id, ~0 empty
  std::vector<uint32_t> coverage;    // fan triangles covering each pixel where no alpha test
                                     // cuts them (tests: 0 or 1 on a watertight surface)
};

ReferenceRaster rasterizeReference(const Scene& scene, const glm::mat4& viewProj, uint32_t width,
                                   uint32_t height);
// The same with the transform given directly (Rasterizer::record's second form).
ReferenceRaster rasterizeReference(const Scene& scene, const RasterTransform& transform,
                                   uint32_t width, uint32_t height);

}  // namespace engine
