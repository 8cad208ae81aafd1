// Environment-map parameterisations for filtered importance sampling (vsgl-math.md section 10):
// the scaled dual-paraboloid map and the equirectangular (latitude-longitude) map, each with its
// exact inverse and its Jacobian, in double and naive on purpose: the oracle for the GLSL
// lookups and for the mip-level rule of env_sampling.h.
//
// This work is based on:
//   [S1] Colbert and Krivanek, "GPU-Based Importance Sampling", GPU Gems 3 ch. 20, 2007
//        (Section 20.4: the dual-paraboloid map scaled by b = 1.2; Equation 14, the distortion
//        d(u), whose text is lost and which section 10 restates as r(z) = 4 b^2 (|z| + 1)^2).
//   [S2] Krivanek and Colbert, "Real-time Shading with Filtered Importance Sampling", EGSR 2008
//        (Section 4: r is the Jacobian of the parameterisation in the mip-level rule).
//   Heidrich and Seidel, "View-independent Environment Maps", 1998 (the paraboloid map).
//
// Texture coordinates: (s, t) in [0, 1]^2 covers one whole map; "unit texture area" below means
// area in these coordinates, so a w x h map has w h texels per unit area.
//
// Dual paraboloid: derivation of the Jacobian (this file's, checked numerically by
// tests/unit/test_env_math.cpp). In a map's own frame (z_m = z for map 0, -z for map 1),
// (u, v) = (x, y) / (1 + z_m) is the stereographic projection from the pole z_m = -1, whose
// inverse is (x, y, z_m) = (2 u, 2 v, 1 - rho^2) / (1 + rho^2), rho^2 = u^2 + v^2, and whose
// area element is d omega = 4 / (1 + rho^2)^2 du dv = (1 + z_m)^2 du dv (1 + z_m = 2 / (1 +
// rho^2)). (s, t) = 1/2 + (u, v) / (2 b) gives du dv = 4 b^2 ds dt, so
//     d omega = r dA,  r = 4 b^2 (1 + z_m)^2  [steradians per unit texture area],
// i.e. r is the solid angle per unit texture area, the direction in which [S1] defines d(u) and
// in which [S2] uses r (the texel solid angle is r / (w h)). In a map's own hemisphere
// z_m = |z|: r runs from 4 b^2 at the rim (z = 0) to 16 b^2 at the pole.
//
// The own hemisphere fills the disc |(s, t) - 1/2| <= 1 / (2 b) (radius 0.4167 for b = 1.2). The
// rest of the square is still a valid, exactly invertible part of the same stereographic map:
// directions of the OTHER hemisphere, down to z_m = (1 - b^2) / (1 + b^2) = -0.180 at the edge
// midpoints and (1 - 2 b^2) / (1 + 2 b^2) = -0.485 at the corners ([S1]'s reason for b > 1:
// a mip texel near the rim averages real neighbours, not black padding).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "shared/environment.h"

namespace gi {

// [S1] Section 20.4 (shaders/shared/environment.h, which the shaders read too).
constexpr double kParaboloidScale = ENV_PARABOLOID_SCALE;

// Sign convention: BOTH maps use (s, t) = 1/2 + (x, y) / (2 b (1 + z_m)), with x along +s and y
// along +t and only z_m flipped. A direction on the equator therefore has the same (s, t) in both
// maps, and a direction just below the equator sits just outside map 0's disc and just inside
// map 1's at the same polar angle: the two maps are glued along the rim without a mirror, so
// switching maps at z = 0 is continuous in (s, t). (Viewed from outside the sphere, map 1 is the
// view from below seen through the sphere, i.e. mirrored; the Heidrich-Seidel back map flips x
// instead, which puts the equator point (1, 0, 0) at s = 1 in one map and s = 0 in the other.)
struct ParaboloidCoordinates {
  uint32_t map = 0;    // 0: z >= 0 (the equator belongs to map 0), 1: z < 0
  glm::dvec2 st{0.5};  // in the map's disc of radius 1 / (2 b) around (1/2, 1/2)
};

// The map of the sign of z and the coordinates there. direction: unit.
ParaboloidCoordinates paraboloidFromDirection(glm::dvec3 direction);

// z in a map's own frame: z for map 0, -z for map 1.
double paraboloidMapZ(glm::dvec3 direction, uint32_t map);

// Coordinates of a unit direction in a GIVEN map, including directions of the other hemisphere
// (then outside the disc, and outside [0, 1]^2 once z_m < -0.180 off the diagonals). Requires
// z_m > -1 (the antipode of the map's pole has no coordinates).
glm::dvec2 paraboloidCoordinatesInMap(glm::dvec3 direction, uint32_t map);

// The exact inverse, for any (s, t) (inside or outside the disc, inside or outside [0, 1]^2):
// the unit direction with paraboloidCoordinatesInMap(direction, map) = st. Unit to rounding for
// every input, since the stereographic inverse is a rational parameterisation of the sphere.
glm::dvec3 paraboloidToDirection(glm::dvec2 st, uint32_t map);

// r = d omega / dA = 4 b^2 (1 + mapZ)^2: steradians per unit texture area (derivation above), at
// a direction whose z in the map's own frame is mapZ (|z| for the map of the sign of z).
double paraboloidSolidAnglePerArea(double mapZ);
// The same, as a function of the texture position: 16 b^2 / (1 + rho^2)^2, (u, v) = b (2 st - 1).
double paraboloidSolidAnglePerArea(glm::dvec2 st);

// ---------------------------------------------------------------------------------------------
// Equirectangular (latitude-longitude) map, y up.
//
// theta = polar angle from +y in [0, pi], phi = azimuth from +x towards +z in [0, 2 pi):
//   direction = (sin theta cos phi, cos theta, sin theta sin phi),  (u, v) = (phi / 2 pi, theta /
//   pi),
// so v = 0 is the top row (straight up, as images are stored top row first), v = 1 straight down,
// and u = 0 (and 1) is the +x meridian. From d omega = sin theta d theta d phi and
// d theta d phi = 2 pi^2 du dv:
//   d omega = 2 pi^2 sin(pi v) du dv  [steradians per unit texture area],
// the same direction of the Jacobian as the paraboloid's r (a texel holds r / (w h) steradians).

// (u, v) of a unit direction, u in [0, 1), v in [0, 1]. The poles (x = z = 0) have u = 0.
glm::dvec2 equirectFromDirection(glm::dvec3 direction);
// The exact inverse for any (u, v); u is periodic, v is taken as is (v outside [0, 1] folds over
// a pole, as the formula does).
glm::dvec3 equirectToDirection(glm::dvec2 uv);
// 2 pi^2 sin(pi v): steradians per unit texture area.
double equirectSolidAnglePerArea(double v);
// The exact solid angle of texel row `row` of a w x h map (every texel of a row holds the same):
// (2 pi / w) (cos theta_0 - cos theta_1), theta_i the row's edges. The h rows sum to 4 pi / w.
double equirectTexelSolidAngle(uint32_t row, uint32_t width, uint32_t height);

}  // namespace gi
