// The CPU twin of adaptive shading's decisions (shaders/gi/adaptive_decide.comp) in double: one
// level's texels, each interpolated from its parents at level L + 1 or queued and shaded. The
// level loop itself (coarsest down to 0) is adaptiveShadingReference.
#pragma once

#include <functional>
#include <vector>

#include "engine/gbuffer_reference.h"
#include "reference/vsgl_shade_reference.h"
#include "shared/adaptive_shading.h"

namespace gi {

// One level's light, row-major over its texels: diffuse without the albedo above level 0 and
// with it at level 0, glossy, the level each texel's light was shaded at, and whether it was
// shaded at the texel's own representative pixel (queued or reused; for a texel whose
// representative pixel sees the sky: 0 light, `sky` set).
struct AdaptiveLevel {
  uint32_t width = 0, height = 0;
  std::vector<glm::dvec3> diffuse, glossy;
  std::vector<uint32_t> origin;
  std::vector<uint8_t> queued;  // 1: shaded at this level
  std::vector<uint8_t> plain;   // 1: queued, and shaded without the glossy term (push.splitGlossy)
  std::vector<uint8_t> exact;   // 1: queued, or reused from the first parent
  std::vector<uint8_t> sky;

  size_t index(glm::uvec2 texel) const { return size_t{texel.y} * width + texel.x; }
};

// The light at a pixel with the diffuse term WITHOUT the albedo (the form the levels keep).
using AdaptiveShade = std::function<IndirectRadiance(glm::uvec2 pixel)>;

// Level `push.level` of a G-buffer (positions rebuilt in double with the push's relative
// unprojection): `parents` is level + 1 (ignored at push.coarsest); queued texels get `shade`
// at their representative pixel.
AdaptiveLevel adaptiveLevelReference(const engine::GBufferData& g,
                                     const gpu::AdaptiveDecidePush& push,
                                     const AdaptiveLevel* parents, const AdaptiveShade& shade);

// Every level from push.coarsest down to 0 (push.level is ignored; element L is level L, and
// level 0 has the albedo applied, as the module's outputs).
std::vector<AdaptiveLevel> adaptiveShadingReference(const engine::GBufferData& g,
                                                    gpu::AdaptiveDecidePush push,
                                                    const AdaptiveShade& shade);

}  // namespace gi
