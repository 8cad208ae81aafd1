// Strategy (c) of the one-bounce path tracer (issue 20): the bounce point y sampled around the
// point where a near-mirror plane reflects the bouncing light towards the receiver x.
//
// Light -> near-mirror y -> diffuse x is a caustic. With a GGX alpha of a few thousandths, y's
// lobe lights x from a few square centimetres around the mirror point y*; x's BRDF sampling (a)
// and the light's rays (b) land there a few times in 10^5 samples, each with a huge weight, so the
// pixel's error is a heavy tail that its sizing runs do not see (the checker's p95 standard error
// was 6x its target). Strategy (c) draws y on the plane around y* with a density shaped like y's
// lobe, and MIS (path_tracer.cpp) combines it with (a) and (b).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "engine/scene.h"

namespace truth {

// A plane qualifies when its material has a specular lobe and a GGX alpha, from its roughness
// factor, of at most kMirrorAlpha (a roughness texture only lowers it: a surface it makes glossy
// in places is missed, which costs samples, not accuracy). Measured at 80x45 with a 3 % target:
// the Cornell box's floor (alpha 0.04) needs 23 % fewer samples with (c), the atrium's concrete
// (0.25) 46 % more, its lobe too wide for (c) to beat (a).
constexpr double kMirrorAlpha = 0.05;
// The largest planes kept (each receiver loops over them).
constexpr size_t kMaxMirrorPlanes = 8;

struct MirrorPlane {
  glm::dvec3 normal{0.0};       // unit
  double offset = 0.0;          // normal . p for p on the plane
  double alpha = 0.0;           // GGX alpha of its triangles' material
  glm::dvec3 lo{0.0}, hi{0.0};  // bounds of its triangles
  double area = 0.0;            // of its triangles, m^2
};

struct MirrorPlanes {
  std::vector<MirrorPlane> planes;  // largest first
  std::vector<int32_t> ofTriangle;  // the plane of each scene triangle, -1 for none
};

// Groups the qualifying triangles by plane: same alpha, every vertex within a micrometre per
// metre of the scene's size of the plane (the positions are fp32). Coplanar triangles that do not
// qualify do not belong to it: (c) only samples near-mirror surface.
MirrorPlanes findMirrorPlanes(const engine::Scene& scene);

// The bouncing light as (c) needs it: a point (a spot; the cone only limits which receivers use
// (c)) or a direction.
struct MirrorLight {
  bool directional = false;
  glm::dvec3 position{0.0};
  glm::dvec3 axis{0.0, 0.0, -1.0};  // unit, the way light travels
  double cosOuter = -1.0;           // spot cone
};
MirrorLight mirrorLight(const engine::Light& light);

// (c) at one receiver x for one plane. Near y*, y's GGX half-vector, written as a slope s (the
// microfacet normal's tangential part over its normal part), moves linearly with y:
// s = J (y - y*). Differentiating h ~ l + v (l, v unit, y to the light and to x) gives
//   J = (1/d_l + 1/d_x) / (2 cos theta) (I - u u^T),
// u the tangential part of l (|u| = sin theta), d_l and d_x the distances from y* to the light
// (infinite for a directional one) and to x; in the plane of incidence J scales by
// c cos theta, across it by c / cos theta, c = (1/d_l + 1/d_x) / 2. (c) draws s from GGX's
// slope distribution P22(s) = 1 / (pi alpha^2 (1 + |s|^2 / alpha^2)^2) (D = P22 / cos^4 of the
// microfacet angle; Walter et al. 2007, Eq. 33) and puts y at y* + J^-1 s, with the density
// P22(J (y - y*)) det J per m^2 of the plane, exact for any y: the linearisation only shapes the
// distribution. Its 1/|s|^4 tail is D's, so y's lobe over this density stays bounded near y*.
struct MirrorLobe {
  int32_t plane = -1;  // index into MirrorPlanes::planes
  double alpha = 0.0;
  glm::dvec3 centre{0.0};       // y*
  glm::dvec3 e1{0.0}, e2{0.0};  // in the plane: along the plane of incidence, across it
  double j1 = 0.0, j2 = 0.0;    // J's eigenvalues, slope per metre along e1 and e2

  // A point on the plane; u1, u2 uniform in [0, 1).
  glm::dvec3 sample(double u1, double u2) const;
  // The density of sample() per m^2 of the plane at y (on the plane).
  double pdf(glm::dvec3 y) const;
};

// The lobe of planes.planes[plane] at x, if x may see the light's reflection in it: x at least
// minHeight off the plane, the light on x's side, and y* within the plane's bounds and the spot's
// cone, both widened by the lobe's reach (kFootprintSlopes alphas of slope, so that the rim of a
// caustic keeps (c)).
constexpr double kFootprintSlopes = 8.0;
std::optional<MirrorLobe> mirrorLobe(const MirrorPlanes& planes, int32_t plane, glm::dvec3 x,
                                     const MirrorLight& light, double minHeight);

}  // namespace truth
