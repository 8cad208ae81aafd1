#include "engine/scene.h"

#include <algorithm>
#include <cmath>

namespace engine {

// translation * rotation * scale of KHR_texture_transform; the rotation's sense is the one its
// own example fixes (offset (0, 1), rotation pi/2 and scale 0.5 map the unit square onto the
// lower-left quadrant, v pointing down).
glm::dvec3 TextureTransform::rowU() const {
  const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
  return {c * scale.x, s * scale.y, offset.x};
}

glm::dvec3 TextureTransform::rowV() const {
  const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
  return {-s * scale.x, c * scale.y, offset.y};
}

Bounds Scene::bounds() const {
  if (positions.empty()) return Bounds{};
  Bounds b{positions.front(), positions.front()};
  for (const glm::vec3& p : positions) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

Camera defaultCamera(const Scene& scene) {
  // Frames the bounding sphere of the bounding box: at distance r / sin(yfov / 2) the sphere
  // touches the top and bottom of the view, so any aspect ratio >= 1 shows all of it.
  constexpr float kYfov = 0.8f;
  constexpr float kMinRadius = 1e-3f;  // a point-like scene still gets a usable camera
  const Bounds b = scene.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max);
  const float radius = std::max(0.5f * glm::length(b.max - b.min), kMinRadius);
  const float distance = radius / std::sin(0.5f * kYfov);

  Camera camera;
  camera.name = "default";
  camera.perspective = true;
  camera.yfov = kYfov;
  camera.aspectRatio = 0.0f;
  // Depth precision scales with znear; 1e-3 of the scene size keeps close-ups unclipped.
  camera.znear = std::max(1e-3f, 1e-3f * radius);
  camera.zfar = 0.0f;
  camera.cameraToWorld = glm::mat4(1.0f);
  camera.cameraToWorld[3] = glm::vec4(centre + glm::vec3(0.0f, 0.0f, distance), 1.0f);
  return camera;
}

glm::vec2 spotFalloff(const Light& light) {
  float cosOuter = std::cos(light.outerConeAngle), cosInner = std::cos(light.innerConeAngle);
  float scale = 1.0f / std::max(1e-3f, cosInner - cosOuter);
  return {scale, -cosOuter * scale};
}

}  // namespace engine
