// The solid angles of the environment's dual-paraboloid texels (docs/techniques/environment.md),
// shared by the environment passes (passes/env_map.h, passes/env_sg.h) and their CPU twins.
#pragma once

#include <cstdint>

namespace gi {

// The SH projection's solid angle of texel (x, y) of an n x n level of `layer`: the part of the
// texel in the layer's OWN hemisphere (rho^2 <= 1 in layer 0, rho^2 < 1 in layer 1, so the
// equator belongs to layer 0 as in env_paraboloid.h), by the midpoint rule on K x K points of
// the texel, K = ENV_SH_TEXEL_SAMPLES (shared/env_map.h): (1 / (n K)^2) sum r(point) over the
// points with rho^2 <= 1. Every direction of the sphere is thus counted once, by the layer that
// owns it, and the rim is a staircase of (n K)^2 cells rather than of whole texels. 0 for texels
// wholly outside the disc. shaders/gi/env_sh.comp computes the same.
double envMapTexelSolidAngle(uint32_t n, uint32_t layer, uint32_t x, uint32_t y);

// The sum of envMapTexelSolidAngle over both layers of an n x n level: 4 pi up to the staircase
// rim (< 1e-4 relative). The GPU pass gets it from the host (a push constant).
double envSgOwnSolidAngle(uint32_t n);

}  // namespace gi
