#include "reference/vsgl_emitter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gi {

namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

double vsglPlanarity(double diffuseSharpness) {
  const double t = std::clamp(
      (diffuseSharpness - VSGL_CORNER_SHARPNESS) / (VSGL_FLAT_SHARPNESS - VSGL_CORNER_SHARPNESS),
      0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

double vsglSpecularNormalisation(double sharpness, double axisDotNormal, double planarity) {
  return (1.0 - planarity) * sgIntegral(sharpness) +
         planarity * kPi * sgClampedCosineIntegralOverPi(sharpness, axisDotNormal);
}

double vsglLambertianNormalisation(double emissionSharpness, double planarity) {
  return (1.0 - planarity) * sgIntegral(emissionSharpness) +
         planarity * 2.0 * kPi * clampedCosineUpperIntegral(emissionSharpness);
}

VsglEmission vsglEmission(const gpu::Vsgl& vsgl, bool planar) {
  VsglEmission out;
  out.diffuse.lambertian = true;
  const glm::dvec3 diffuseAxis(vsgl.diffuse.axisSharpness);
  const double axisLength = glm::length(diffuseAxis);
  if (!planar || !(vsgl.diffuse.power.a > 0.0f) || !(axisLength > 0.0)) return out;
  const glm::dvec3 normal = diffuseAxis / axisLength;
  const double beta = vsglPlanarity(vsgl.diffuse.axisSharpness.w);
  out.diffuse.plane = out.specular.plane = beta * normal;
  out.diffuse.flatness = out.specular.flatness = 1.0 - beta;
  const glm::dvec3 specularAxis(vsgl.specular.axisSharpness);
  const double specularLength = glm::length(specularAxis);
  // A lobe below the plane is normalised as if along the horizon (vsgl_emitter.glsl).
  const double cosine =
      specularLength > 0.0 ? std::max(glm::dot(specularAxis, normal) / specularLength, 0.0) : 0.0;
  out.specular.normalisation =
      vsglSpecularNormalisation(vsgl.specular.axisSharpness.w, cosine, beta);
  return out;
}

}  // namespace gi
