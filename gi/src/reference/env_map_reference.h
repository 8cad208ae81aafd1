// The CPU twin of the environment conversion (docs/techniques/environment.md, passes 1 and 2):
// an equirectangular image, or a radiance function, turned into the scaled dual-paraboloid map
// of shaders/shared/environment.h with its box-filtered mip chain, and the map's SH radiance
// coefficients. Double, naive on purpose. GPU passes: gi/src/passes/env_map.h
// (shaders/gi/env_paraboloid.comp, env_mip_reduce.comp, env_sh.comp), which
// tests/gpu/test_env_map.cpp holds to these within stated fp32 bounds.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "engine/image_io.h"
#include "common/env_texels.h"
#include "reference/sh_irradiance.h"

namespace gi {

// Two layers of size x size texels at level 0 (layer 0: z >= 0, layer 1: z < 0), every level
// down to 1 x 1.
struct EnvMapReference {
  uint32_t size = 0;
  // levels[l][(layer * n + y) * n + x], n = size >> l: RGB radiance.
  std::vector<std::vector<glm::dvec3>> levels;

  uint32_t levelSize(uint32_t level) const { return size >> level; }
  const glm::dvec3& texel(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
    const uint32_t n = levelSize(level);
    return levels[level][(size_t{layer} * n + y) * n + x];
  }
};

// Level 0 from the radiance function of a unit direction, as the conversion shader fills it,
// then the mips. `size`: a power of two (else engine::Error).
//
// Level 0: texel (x, y) of a layer covers s in [x, x + 1] / S and t in [y, y + 1] / S (row y is
// t, as Vulkan addresses images), and holds the mean of the radiance at the directions
// paraboloidToDirection of the 2 x 2 points (x + {1/4, 3/4}, y + {1/4, 3/4}) / S. Texels
// outside a layer's disc get the directions of the other hemisphere that the same mapping gives
// them (why b = 1.2: mip texels at the rim average real directions). Level l + 1 is the exact
// 2 x 2 box mean of level l, per layer (shaders/shared/mip_reduce.h).
EnvMapReference envMapFromFunction(uint32_t size,
                                   const std::function<glm::dvec3(glm::dvec3)>& radiance);
// Level 0 from an equirectangular image (engine::ImageRgba32f, linear RGB, the conventions of
// env_paraboloid.h), read bilinearly as the conversion shader does, then the mips.
EnvMapReference envMapFromEquirect(const engine::ImageRgba32f& equirect, uint32_t size);

// The bilinear equirect read of the conversion: texel centres at ((i + 1/2) / w, (j + 1/2) / h),
// u wraps around (the +x meridian is continuous), v is clamped to the first and last rows (the
// poles). rgb; alpha is ignored. `equirect` must be non-empty.
glm::dvec3 equirectBilinear(const engine::ImageRgba32f& equirect, glm::dvec2 uv);


// The map's 9 SH radiance coefficients, as the SH pass projects them: every texel of `level`
// with its radiance at the direction of its centre, weighted by the solid angle of its part in
// its layer's own hemisphere (envMapTexelSolidAngle). A texel straddling the rim brings its
// mean over both hemispheres, counted with its own part's solid angle only. The weights sum to
// 4 pi only approximately (the midpoint rule on a staircase disc);
// tests/unit/test_env_map_reference.cpp states how closely.
ShRgb envMapSh(const EnvMapReference& map, uint32_t level);

}  // namespace gi
