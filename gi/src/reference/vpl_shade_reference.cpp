#include "reference/vpl_shade_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/brdf_reference.h"
#include "reference/vsgl_emitter.h"

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;

struct PointLight {
  glm::dvec3 position{0.0};
  double area = 0.0;         // the disc's, 4 pi v
  glm::dvec3 normal{0.0};    // 0 without diffuse power
  glm::dvec3 diffuse{0.0};   // Phi_d
  glm::dvec3 specular{0.0};  // Phi_s
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double sharpness = 0.0;
  glm::dvec3 plane{0.0};  // the planar emitter's beta n (vsglEmission)
  double flatness = 1.0;  // 1 - beta
};

PointLight pointLight(const gpu::Vsgl& v, bool diffuseLobesOnly) {
  PointLight p;
  const bool hasNormal = v.diffuse.power.a > 0.0f;
  const gpu::VsglLobe& lobe = hasNormal ? v.diffuse : v.specular;
  p.position = glm::dvec3(lobe.meanVariance);
  p.area = 4.0 * kPi * double(lobe.meanVariance.w);
  if (hasNormal) p.normal = glm::normalize(glm::dvec3(v.diffuse.axisSharpness));
  p.diffuse = glm::dvec3(v.diffuse.power);
  if (!diffuseLobesOnly) p.specular = glm::dvec3(v.specular.power);
  p.axis = glm::dvec3(v.specular.axisSharpness);
  p.sharpness = v.specular.axisSharpness.w;
  // The planar emitter's plane (vsglEmitterPlane on the GPU); its normalisation is taken per
  // pair below, at the widened sharpness.
  const VsglLobeEmission emission = vsglEmission(v, true).specular;
  p.plane = emission.plane;
  p.flatness = emission.flatness;
  return p;
}

// Radiant intensity along unit `toward` (from the VPL), the specular SG widened by `spread`.
glm::dvec3 intensity(const PointLight& p, glm::dvec3 toward, double spread) {
  glm::dvec3 i = p.diffuse * (std::max(glm::dot(p.normal, toward), 0.0) / kPi);
  if (p.specular == glm::dvec3(0.0)) return i;
  const double lambda = p.sharpness / (1.0 + p.sharpness * spread);
  const double g = std::exp(lambda * (glm::dot(p.axis, toward) - 1.0));
  const double beta = 1.0 - p.flatness;
  const double cut = p.flatness + std::max(glm::dot(p.plane, toward), 0.0);
  const double axisDotNormal = beta > 0.0 ? std::max(glm::dot(p.axis, p.plane) / beta, 0.0) : 0.0;
  return i + p.specular * (g * cut / vsglSpecularNormalisation(lambda, axisDotNormal, beta));
}

}  // namespace

IndirectRadiance shadeVplsReference(const ShadeReceiver& receiver, std::span<const gpu::Vsgl> vpls,
                                    bool glossy, bool diffuseLobesOnly,
                                    const VsglVisibility& visibility) {
  const double alpha = std::max(receiver.roughness * receiver.roughness, engine::kMinAlpha);
  IndirectRadiance out;
  glm::dvec3 diffuseSum(0.0);
  for (uint32_t k = 0; k < vpls.size(); ++k) {
    const PointLight p = pointLight(vpls[k], diffuseLobesOnly);
    const glm::dvec3 d = p.position - receiver.position;
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0.0)) continue;
    const glm::dvec3 w = d / std::sqrt(d2);  // receiver -> VPL
    const double cosine = glm::dot(receiver.normal, w);
    if (cosine <= 0.0) continue;
    const double v = visibility ? visibility(k) : 1.0;
    if (v == 0.0) continue;
    // The disc's on-axis form factor instead of 1 / d^2, its angular variance widening both
    // glossy lobes (vpl_shade.comp).
    const double spread = p.area / (4.0 * kPi * d2);
    const glm::dvec3 arriving = intensity(p, -w, spread) * (v / (d2 + p.area / kPi));
    diffuseSum += arriving * (cosine / kPi);
    if (glossy) {
      const double widened = std::sqrt(std::sqrt(alpha * alpha + spread));
      out.glossy += arriving * cosine *
                    engine::ggxSpecular(receiver.normal, receiver.view, w, receiver.f0,
                                        receiver.f90, widened);
    }
  }
  out.diffuse = diffuseSum * receiver.albedo;
  return out;
}

}  // namespace gi
