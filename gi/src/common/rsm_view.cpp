#include "common/rsm_view.h"

#include <cmath>
#include <numbers>

#include "engine/error.h"

namespace gi {

using engine::Error;

double frustumSolidAngle(double halfAngle) {
  double s = std::sin(halfAngle);
  return 4.0 * std::asin(s * s);
}

RsmView makeRsmView(const engine::Scene& scene, const engine::Light& light, uint32_t size) {
  return makeRsmView(scene.bounds(), light, size);
}

namespace {

// A square perspective frustum of half angle `halfAngle` from `position` along unit `axis`.
RsmView perspectiveView(const engine::Bounds& bounds, glm::vec3 position, glm::vec3 axis,
                        float halfAngle, uint32_t size) {
  RsmView r;
  r.axis = axis;
  r.perspective = true;
  r.origin = position;
  r.tanHalfAngle = std::tan(halfAngle);
  const float texelSide = 2.0f * r.tanHalfAngle / static_cast<float>(size);
  r.texelArea = texelSide * texelSide;
  const engine::DepthRange range = engine::enclosingDepthRange(bounds, position);
  const glm::mat4 proj = engine::perspectiveVulkan(2.0f * halfAngle, 1.0f, range.znear, range.zfar);
  const glm::mat4 rotation = engine::lookAlong(glm::vec3(0.0f), axis, engine::upVectorFor(axis));
  const glm::mat4 view = engine::lookAlong(position, axis, engine::upVectorFor(axis));
  r.view = engine::makeView(view, proj, size, size);
  r.raster = {proj * rotation, position};
  r.invViewProjRelative = glm::inverse(proj * rotation);
  return r;
}

constexpr glm::vec3 kCubeFaceAxes[kCubeFaces] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                                 {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};

}  // namespace

std::vector<RsmView> makeRsmViews(const engine::Bounds& bounds, const engine::Light& light,
                                  uint32_t size) {
  if (light.type != engine::LightType::Point) return {makeRsmView(bounds, light, size)};
  std::vector<RsmView> faces;
  for (const glm::vec3& axis : kCubeFaceAxes)
    faces.push_back(
        perspectiveView(bounds, light.position, axis, 0.25f * std::numbers::pi_v<float>, size));
  return faces;
}

RsmView makeRsmView(const engine::Bounds& bounds, const engine::Light& light, uint32_t size) {
  RsmView r;
  r.axis = glm::normalize(light.direction);
  const float texels = static_cast<float>(size);
  if (light.type == engine::LightType::Spot) {
    if (light.outerConeAngle > kMaxRsmHalfAngle)
      throw Error("light '" + light.name + "': spot cone " + std::to_string(light.outerConeAngle) +
                  " rad is wider than the RSM supports (" + std::to_string(kMaxRsmHalfAngle) +
                  " rad)");
    return perspectiveView(bounds, light.position, r.axis, light.outerConeAngle, size);
  } else if (light.type == engine::LightType::Directional) {
    engine::EnclosingOrtho o = engine::enclosingOrthographic(bounds, r.axis);
    r.perspective = false;
    r.origin = o.eye;
    float texelSide = 2.0f * o.halfExtent / texels;
    r.texelArea = texelSide * texelSide;
    glm::mat4 rotation = o.view;
    rotation[3] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    r.view = engine::makeView(o.view, o.proj, size, size);
    r.raster = {o.proj * rotation, o.eye};
    r.invViewProjRelative = glm::inverse(o.proj * rotation);
  } else {
    throw Error("light '" + light.name + "': a point light has six RSM views (makeRsmViews)");
  }
  return r;
}

FluxSource lightFluxSource(const engine::Light& light) {
  FluxSource source;
  source.radiance = light.color * light.intensity;
  source.falloff =
      light.type == engine::LightType::Spot ? engine::spotFalloff(light) : glm::vec2(0.0f, 1.0f);
  // KHR_lights_punctual: a directional light has no range. A point light has no falloff.
  source.range = light.type == engine::LightType::Directional ? 0.0f : light.range;
  return source;
}

RsmView cameraImportanceView(const engine::View& view) {
  RsmView r;
  r.view = view;
  glm::mat4 rotation = view.view;
  rotation[3] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  const engine::RelativeUnprojection unprojection = engine::relativeUnprojection(view);
  r.invViewProjRelative = unprojection.invViewProjRelative;
  r.origin = unprojection.eye;
  r.raster = {view.proj * rotation, r.origin};
  const glm::mat4 cameraToWorld = glm::inverse(view.view);
  r.axis = -glm::normalize(glm::vec3(cameraToWorld[2]));
  r.perspective = view.proj[3][3] == 0.0f;  // a perspective projection has no constant w term
  // Pixel side on the plane at unit distance (or in metres) from the projection's own scale,
  // so the camera's aspect ratio, however it was chosen, is honoured.
  float sideX = 2.0f / (view.proj[0][0] * static_cast<float>(view.width));
  float sideY = 2.0f / (std::abs(view.proj[1][1]) * static_cast<float>(view.height));
  r.tanHalfAngle = 1.0f / std::abs(view.proj[1][1]);
  r.texelArea = sideX * sideY;
  return r;
}

}  // namespace gi
