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

std::optional<glm::mat4> rigidCameraFrame(const glm::mat4& floats) {
  const glm::dmat4 world(floats);
  // Already rigid to float precision (a frame this function or a host made): kept as its
  // floats, so that a camera written to a file and read back is the same camera to the bit.
  const glm::dvec3 cx(world[0]), cy(world[1]), cz(world[2]);
  auto near = [](double a, double b) { return std::abs(a - b) <= 1e-6; };
  if (near(glm::dot(cx, cx), 1.0) && near(glm::dot(cy, cy), 1.0) && near(glm::dot(cz, cz), 1.0) &&
      near(glm::dot(cx, cy), 0.0) && near(glm::dot(cy, cz), 0.0) && near(glm::dot(cz, cx), 0.0) &&
      glm::dot(glm::cross(cx, cy), cz) > 0.0 && world[0][3] == 0.0 && world[1][3] == 0.0 &&
      world[2][3] == 0.0 && world[3][3] == 1.0)
    return floats;
  // Z, the viewing axis, keeps its direction exactly; Y is its nearest orthogonal direction.
  auto unit = [](const glm::dvec3& v) -> std::optional<glm::dvec3> {
    const double length = glm::length(v);
    if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
    return v / length;
  };
  const auto z = unit(glm::dvec3(world[2]));
  if (!z) return std::nullopt;
  const auto y = unit(glm::dvec3(world[1]) - glm::dot(glm::dvec3(world[1]), *z) * *z);
  if (!y) return std::nullopt;
  const glm::dvec3 x = glm::cross(*y, *z);
  return glm::mat4(
      glm::dmat4(glm::dvec4(x, 0.0), glm::dvec4(*y, 0.0), glm::dvec4(*z, 0.0), world[3]));
}

std::optional<glm::vec3> fileLightDirection(const glm::vec3& direction) {
  const double length = glm::length(glm::dvec3(direction));
  if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
  if (std::abs(length - 1.0) <= 1e-6) return direction;
  return glm::vec3(glm::dvec3(direction) / length);
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
