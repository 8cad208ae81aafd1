#include "default_light.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>

#include "cli_values.h"
#include "engine/error.h"

namespace samples {

namespace {

constexpr float kSunElevation = 50.0f * glm::pi<float>() / 180.0f;
constexpr float kSunAzimuthTurn = 45.0f * glm::pi<float>() / 180.0f;
constexpr float kMaxHeadlightCone = 1.2f;  // radians, inside the RSM's 1.3 (gi/src/passes/rsm.h)

engine::Camera sceneCamera(const engine::Scene& scene) {
  return scene.cameras.empty() ? engine::defaultCamera(scene) : scene.cameras.front();
}

glm::vec3 cameraForward(const engine::Camera& camera) {
  return glm::normalize(-glm::vec3(camera.cameraToWorld[2]));
}

}  // namespace

LightChoice parseLightChoice(std::string_view option, std::string_view text) {
  return parseChoice<LightChoice>(option, text,
                                  {{"auto", LightChoice::Auto},
                                   {"sun", LightChoice::Sun},
                                   {"headlight", LightChoice::Headlight},
                                   {"none", LightChoice::None}});
}

engine::Light defaultSun(const engine::Scene& scene) {
  const glm::vec3 forward = cameraForward(sceneCamera(scene));
  glm::vec3 horizontal(forward.x, 0.0f, forward.z);
  // A camera looking straight down or up has no horizontal forward: glTF's -Z stands in.
  horizontal =
      glm::length(horizontal) > 1e-3f ? glm::normalize(horizontal) : glm::vec3(0.0f, 0.0f, -1.0f);
  // Turned 45 degrees to the camera's right (clockwise seen from +y).
  const float c = std::cos(kSunAzimuthTurn), s = std::sin(kSunAzimuthTurn);
  const glm::vec3 travel(c * horizontal.x - s * horizontal.z, 0.0f,
                         s * horizontal.x + c * horizontal.z);
  engine::Light sun;
  sun.name = "default sun";
  sun.type = engine::LightType::Directional;
  sun.direction = glm::normalize(std::cos(kSunElevation) * travel +
                                 glm::vec3(0.0f, -std::sin(kSunElevation), 0.0f));
  sun.intensity = kDefaultIlluminance;
  return sun;
}

engine::Light headlight(const engine::Scene& scene, float aspect) {
  const engine::Camera camera = sceneCamera(scene);
  const engine::Bounds b = scene.bounds();
  engine::Light spot;
  spot.name = "headlight";
  spot.type = engine::LightType::Spot;
  spot.position = glm::vec3(camera.cameraToWorld[3]);
  spot.direction = cameraForward(camera);
  const float halfDiagonal =
      camera.perspective
          ? std::atan(std::tan(0.5f * camera.yfov) * std::sqrt(1.0f + aspect * aspect))
          : 0.5f;
  spot.outerConeAngle = std::min(1.05f * halfDiagonal, kMaxHeadlightCone);
  spot.innerConeAngle = 0.8f * spot.outerConeAngle;
  const float d = glm::length(0.5f * (b.min + b.max) - spot.position);
  spot.intensity = kDefaultIlluminance * std::max(d * d, 1e-4f);
  return spot;
}

std::string applyLightChoice(engine::Scene& scene, LightChoice choice, bool environment,
                             float aspect) {
  char line[256];
  switch (choice) {
    case LightChoice::Auto:
      if (!scene.lights.empty() || environment) return "";
      scene.lights = {defaultSun(scene)};
      std::snprintf(line, sizeof(line),
                    "light: %s has no light; added the default sun (--light auto), %.3g W/m^2 "
                    "along (%.2f, %.2f, %.2f)",
                    scene.source.c_str(), double(kDefaultIlluminance),
                    double(scene.lights[0].direction.x), double(scene.lights[0].direction.y),
                    double(scene.lights[0].direction.z));
      return line;
    case LightChoice::Sun: {
      const size_t own = scene.lights.size();
      scene.lights = {defaultSun(scene)};
      std::snprintf(line, sizeof(line),
                    "light: the default sun instead of the file's %zu lights (--light sun), %.3g "
                    "W/m^2 along (%.2f, %.2f, %.2f)",
                    own, double(kDefaultIlluminance), double(scene.lights[0].direction.x),
                    double(scene.lights[0].direction.y), double(scene.lights[0].direction.z));
      return line;
    }
    case LightChoice::Headlight: {
      const size_t own = scene.lights.size();
      scene.lights = {headlight(scene, aspect)};
      std::snprintf(line, sizeof(line),
                    "light: a headlight at the camera instead of the file's %zu lights "
                    "(--light headlight), %.3g W/sr, cone %.2f rad",
                    own, double(scene.lights[0].intensity), double(scene.lights[0].outerConeAngle));
      return line;
    }
    case LightChoice::None:
      if (scene.lights.empty() && !environment)
        throw engine::Error(scene.source +
                            ": no light (KHR_lights_punctual) and no --environment to render by; "
                            "use --light auto, sun or headlight, or --environment");
      return "";
  }
  return "";
}

}  // namespace samples
