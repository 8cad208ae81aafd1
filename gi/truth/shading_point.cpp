#include "shading_point.h"

#include <cmath>

namespace truth {

ShadingPoint shadingPoint(const engine::Scene& scene, const RayHit& hit, glm::dvec3 origin,
                          glm::dvec3 rayDir, engine::BackFaces backFaces) {
  glm::dvec3 p[3];
  for (int k = 0; k < 3; ++k) p[k] = scene.positions[scene.indices[3 * size_t{hit.triangle} + k]];
  const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const glm::dvec3 q = glm::cross(rayDir, e2);
  const double det = glm::dot(e1, q);
  glm::dvec2 bc = hit.barycentrics;
  if (std::abs(det) > 0.0) {
    const glm::dvec3 o = origin - p[0];
    bc = glm::dvec2(glm::dot(o, q), glm::dot(rayDir, glm::cross(o, e1))) / det;
  }
  ShadingPoint s;
  s.position = p[0] + bc.x * e1 + bc.y * e2;
  s.geometricNormal = glm::normalize(glm::cross(e1, e2));
  if (glm::dot(s.geometricNormal, rayDir) > 0.0) s.geometricNormal = -s.geometricNormal;
  s.surface = engine::surfaceAt(scene, hit.triangle, bc, rayDir, backFaces);
  return s;
}

std::optional<PrimaryHit> primaryHit(const engine::Scene& scene, const EmbreeScene& rays,
                                     const engine::View& view, size_t pixel) {
  const auto px = static_cast<uint32_t>(pixel % view.width),
             py = static_cast<uint32_t>(pixel / view.width);
  const engine::CameraRay ray = engine::cameraRayReference(view, glm::dvec2(px + 0.5, py + 0.5));
  const RayHit hit = rays.intersect(ray.origin, ray.dir);
  if (!hit.hit) return std::nullopt;
  return PrimaryHit{ray, shadingPoint(scene, hit, ray.origin, ray.dir)};
}

}  // namespace truth
