#include "mirror_planes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "engine/brdf_reference.h"
#include "engine/orthonormal_basis.h"

namespace truth {
namespace {

constexpr double kPi = std::numbers::pi;

// A coarse key for a triangle's plane (normal and offset to 1e-3, the normal's sign made that of
// its largest component), so that finding a triangle's plane only tests the planes of its bucket.
// A plane that straddles two buckets becomes two planes: (c) stays exact, each samples its own
// triangles.
using PlaneKey = std::tuple<int64_t, int64_t, int64_t, int64_t, double>;
PlaneKey planeKey(glm::dvec3 n, double offset, double alpha, double scale) {
  const int axis = std::abs(n.x) >= std::max(std::abs(n.y), std::abs(n.z)) ? 0
                   : std::abs(n.y) >= std::abs(n.z)                        ? 1
                                                                           : 2;
  if (n[axis] < 0.0) {
    n = -n;
    offset = -offset;
  }
  auto q = [](double v) { return static_cast<int64_t>(std::llround(v * 1e3)); };
  return {q(n.x), q(n.y), q(n.z), q(offset / scale), alpha};
}

}  // namespace

MirrorPlanes findMirrorPlanes(const engine::Scene& scene) {
  const engine::Bounds bounds = scene.bounds();
  const double scale = std::max(glm::length(glm::dvec3(bounds.max - bounds.min)), 1.0);
  const double tolerance = 1e-6 * scale;
  const size_t triangles = scene.indices.size() / 3;
  std::vector<MirrorPlane> found;
  std::vector<int32_t> ofTriangle(triangles, -1);
  std::map<PlaneKey, std::vector<int32_t>> buckets;
  for (size_t t = 0; t < triangles; ++t) {
    const engine::Material& m = scene.materials[scene.triangleMaterial[t]];
    const double alpha = std::max(double(m.roughnessFactor) * m.roughnessFactor, engine::kMinAlpha);
    if (alpha > kMirrorAlpha || (m.metallicFactor <= 0.0f && m.specularFactor <= 0.0f)) continue;
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = scene.positions[scene.indices[3 * t + k]];
    const glm::dvec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double twiceArea = glm::length(c);
    if (twiceArea <= 0.0) continue;
    const glm::dvec3 n = c / twiceArea;
    std::vector<int32_t>& bucket = buckets[planeKey(n, glm::dot(n, p[0]), alpha, scale)];
    auto holds = [&](int32_t k) {
      const MirrorPlane& plane = found[k];
      return std::all_of(p, p + 3, [&](glm::dvec3 v) {
        return std::abs(glm::dot(plane.normal, v) - plane.offset) <= tolerance;
      });
    };
    auto it = std::find_if(bucket.begin(), bucket.end(), holds);
    if (it == bucket.end()) {
      bucket.push_back(static_cast<int32_t>(found.size()));
      found.push_back({n, glm::dot(n, p[0]), alpha, p[0], p[0], 0.0});
      it = bucket.end() - 1;
    }
    MirrorPlane& plane = found[*it];
    for (const glm::dvec3& v : p) {
      plane.lo = glm::min(plane.lo, v);
      plane.hi = glm::max(plane.hi, v);
    }
    plane.area += 0.5 * twiceArea;
    ofTriangle[t] = *it;
  }
  // The largest planes, renumbered.
  std::vector<int32_t> order(found.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int32_t>(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](int32_t a, int32_t b) { return found[a].area > found[b].area; });
  order.resize(std::min(order.size(), kMaxMirrorPlanes));
  std::vector<int32_t> renumber(found.size(), -1);
  MirrorPlanes kept;
  for (const int32_t k : order) {
    renumber[k] = static_cast<int32_t>(kept.planes.size());
    kept.planes.push_back(found[k]);
  }
  kept.ofTriangle.resize(triangles);
  for (size_t t = 0; t < triangles; ++t)
    kept.ofTriangle[t] = ofTriangle[t] < 0 ? -1 : renumber[ofTriangle[t]];
  return kept;
}

MirrorLight mirrorLight(const engine::Light& light) {
  MirrorLight m;
  m.directional = light.type == engine::LightType::Directional;
  m.position = glm::dvec3(light.position);
  m.axis = glm::normalize(glm::dvec3(light.direction));
  if (light.type == engine::LightType::Spot) m.cosOuter = std::cos(double(light.outerConeAngle));
  return m;
}

glm::dvec3 MirrorLobe::sample(double u1, double u2) const {
  // The inverse of P22's radial distribution, |s|^2 / (alpha^2 + |s|^2).
  const double r = alpha * std::sqrt(u1 / (1.0 - u1)), phi = 2.0 * kPi * u2;
  return centre + (r * std::cos(phi) / j1) * e1 + (r * std::sin(phi) / j2) * e2;
}

double MirrorLobe::pdf(glm::dvec3 y) const {
  const glm::dvec3 d = y - centre;
  const double s1 = j1 * glm::dot(d, e1), s2 = j2 * glm::dot(d, e2);
  const double t = 1.0 + (s1 * s1 + s2 * s2) / (alpha * alpha);
  return j1 * j2 / (kPi * alpha * alpha * t * t);
}

std::optional<MirrorLobe> mirrorLobe(const MirrorPlanes& planes, int32_t plane, glm::dvec3 x,
                                     const MirrorLight& light, double minHeight) {
  const MirrorPlane& p = planes.planes[plane];
  const double height = glm::dot(p.normal, x) - p.offset;
  if (std::abs(height) <= minHeight) return std::nullopt;    // x on the plane sees none of it
  const glm::dvec3 n = height > 0.0 ? p.normal : -p.normal;  // towards x
  const double b = std::abs(height);
  MirrorLobe lobe;
  lobe.plane = plane;
  lobe.alpha = p.alpha;
  double inverseLightDistance = 0.0;
  if (light.directional) {
    const glm::dvec3 l = -light.axis;
    const double cosTheta = glm::dot(n, l);
    if (cosTheta <= 0.0) return std::nullopt;
    // x sees y* along the mirror direction of l.
    lobe.centre = x - (b / cosTheta) * (2.0 * cosTheta * n - l);
  } else {
    const double a = glm::dot(n, light.position - x) + b;  // the light's height
    if (a <= 0.0) return std::nullopt;
    // The segment from x to the light's mirror image crosses the plane at y*.
    const glm::dvec3 image = light.position - 2.0 * a * n;
    lobe.centre = x + (b / (a + b)) * (image - x);
    inverseLightDistance = 1.0 / glm::length(light.position - lobe.centre);
  }
  const glm::dvec3 toX = x - lobe.centre;
  const double dx = glm::length(toX);
  const double cosTheta = b / dx;
  const glm::dvec3 tangential = toX - b * n;
  lobe.e1 = glm::length(tangential) > 1e-9 * dx ? glm::normalize(tangential)
                                                : engine::orthonormalBasis(n).tangent;
  lobe.e2 = glm::cross(n, lobe.e1);
  const double c = 0.5 * (inverseLightDistance + 1.0 / dx);
  lobe.j1 = c * cosTheta;
  lobe.j2 = c / cosTheta;
  // The lobe's reach on the plane along its long axis, e1.
  const double reach = kFootprintSlopes * lobe.alpha / lobe.j1;
  if (glm::any(glm::lessThan(lobe.centre, p.lo - reach)) ||
      glm::any(glm::greaterThan(lobe.centre, p.hi + reach)))
    return std::nullopt;
  if (!light.directional && light.cosOuter > -1.0) {
    const glm::dvec3 w = glm::normalize(lobe.centre - light.position);
    const double angle = std::acos(std::clamp(glm::dot(w, light.axis), -1.0, 1.0));
    if (angle > std::acos(light.cosOuter) + reach * inverseLightDistance) return std::nullopt;
  }
  return lobe;
}

}  // namespace truth
