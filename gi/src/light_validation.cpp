#include "light_validation.h"

#include <cmath>
#include <cstdio>

#include "passes/rsm.h"

namespace gi {

namespace {

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string number(float v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", double(v));
  return text;
}

std::string vector(glm::vec3 v) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return text;
}

}  // namespace

std::string validateLight(const Light& light, const std::string& field) {
  const std::string f = field + ".";
  if (light.type != Light::Type::Spot && light.type != Light::Type::Directional &&
      light.type != Light::Type::Point)
    return f + "type: " + std::to_string(uint32_t(light.type)) +
           " is none of Spot, Directional, Point";
  if (light.type != Light::Type::Directional && !finite(light.position))
    return f + "position: " + vector(light.position) + " is not finite";
  if (light.type != Light::Type::Point &&
      (!finite(light.direction) || !(glm::length(light.direction) > 0.0f)))
    return f + "direction: " + vector(light.direction) + " must be finite and non-zero";
  if (!finite(light.color) ||
      !(light.color.r >= 0.0f && light.color.g >= 0.0f && light.color.b >= 0.0f))
    return f + "color: " + vector(light.color) + " must be finite and >= 0";
  if (!std::isfinite(light.intensity) || !(light.intensity >= 0.0f))
    return f + "intensity: " + number(light.intensity) + " must be finite and >= 0";
  if (!std::isfinite(light.range) || !(light.range >= 0.0f))
    return f + "range: " + number(light.range) + " m must be finite and >= 0 (0 = no range)";
  if (light.type == Light::Type::Spot) {
    if (!(light.outerConeAngle > 0.0f && light.outerConeAngle <= kMaxRsmHalfAngle))
      return f + "outerConeAngle: " + number(light.outerConeAngle) + " rad is outside (0, " +
             number(kMaxRsmHalfAngle) + "] (the RSM's widest cone)";
    if (!(light.innerConeAngle >= 0.0f && light.innerConeAngle < light.outerConeAngle))
      return f + "innerConeAngle: " + number(light.innerConeAngle) +
             " rad is outside [0, outerConeAngle = " + number(light.outerConeAngle) + ")";
  }
  return "";
}

}  // namespace gi
