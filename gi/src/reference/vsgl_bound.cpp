#include "reference/vsgl_bound.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "reference/sg_math.h"
#include "reference/vsgl_emitter.h"

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;
// The spot's tail (vsgl_bound.glsl kVsglBoundTail): outside the cone where the spot
// G(w; xi, lambda_s) >= kTail, the spot is bounded by kTail.
constexpr double kTail = 1e-4;
// Radians added to the cone (vsgl_bound.glsl kVsglBoundAngleMargin): the fp32 angles between
// near-parallel unit vectors are off by up to ~5e-4 (acos of a dot product rounded to 1e-7).
constexpr double kAngleMargin = 1e-3;
// Over the tabulated albedo (vsgl_bound.glsl kVsglBoundAlbedoMargin).
constexpr double kAlbedoMargin = 1.1;

double angleBetween(glm::dvec3 a, glm::dvec3 b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
}

double largest(glm::dvec3 c) {
  return std::max({c.r, c.g, c.b});
}

}  // namespace

VsglReceivers vsglReceivers(std::span<const ShadeReceiver> receivers, bool glossy) {
  VsglReceivers g;
  if (receivers.empty()) return g;
  glm::dvec3 lo = receivers[0].position, hi = lo, sum(0.0);
  for (const ShadeReceiver& r : receivers) {
    lo = glm::min(lo, r.position);
    hi = glm::max(hi, r.position);
    sum += r.normal;
  }
  g.centre = 0.5 * (lo + hi);
  g.radius = 0.5 * glm::length(hi - lo);
  const double length2 = glm::dot(sum, sum);
  g.normalAxis = length2 > 0.0 ? sum / std::sqrt(length2) : glm::dvec3(0.0, 0.0, 1.0);
  g.normalAngle = 0.0;
  g.albedo = 0.0;
  g.fresnel = 0.0;
  g.alpha = 1.0;
  g.viewCosine = 1.0;
  g.specularAlbedo = 0.0;
  for (const ShadeReceiver& r : receivers) {
    g.normalAngle = std::max(g.normalAngle, angleBetween(r.normal, g.normalAxis));
    g.albedo = std::max(g.albedo, largest(r.albedo));
    const double alpha = std::max(r.roughness * r.roughness, 1e-3);
    const double nv = std::max(glm::dot(r.normal, r.view), 1e-4);
    g.alpha = std::min(g.alpha, alpha);
    g.viewCosine = std::min(g.viewCosine, nv);
    if (!glossy) continue;
    g.fresnel = std::max({g.fresnel, largest(r.f0), r.f90});
    const glm::dvec2 table = ggxSpecularAlbedo(nv, alpha);
    g.specularAlbedo =
        std::max(g.specularAlbedo, largest(r.f90 * table.x + r.f0 * (table.y - table.x)));
  }
  if (!(length2 > 1e-6)) g.normalAngle = kPi;
  return g;
}

VsglLobeBound vsglLobeBound(const gpu::VsglLobe& lobe, const VsglReceivers& group,
                            const VsglLobeEmission& emitted) {
  const double power = std::max({lobe.power.r, lobe.power.g, lobe.power.b});
  if (!(power > 0.0)) return {};
  const glm::dvec3 mean(lobe.meanVariance);
  const glm::dvec3 rawAxis(lobe.axisSharpness);
  const double axisLength = glm::length(rawAxis);
  const glm::dvec3 axis = axisLength > 0.0 ? rawAxis / axisLength : glm::dvec3(0.0, 0.0, 1.0);
  // The emission's sharpness and normalisation (the foreshortening f <= 1 only lowers the light:
  // I carries f and the spot's variance f v never exceeds v, planar-emitters.md).
  const double variance = lobe.meanVariance.w;
  // A Lambertian lobe's emission sharpness lies in [(1 - beta) lambda, lambda] and its N is least
  // at lambda: the widest emission with the least N bounds it.
  const double sharpness =
      emitted.lambertian ? emitted.flatness * lobe.axisSharpness.w : lobe.axisSharpness.w;
  const double normalisation =
      emitted.lambertian
          ? vsglLambertianNormalisation(lobe.axisSharpness.w, 1.0 - emitted.flatness)
          : (emitted.normalisation < 0.0 ? sgIntegral(sharpness) : emitted.normalisation);

  const glm::dvec3 toLight = mean - group.centre;
  const double centreDistance = glm::length(toLight);
  // Every receiver is at d >= nearest; v' = max(v, d^2 2^-41, FLT_MIN) is least there.
  const double nearest = std::max(centreDistance - group.radius, 0.0);
  const double nearest2 = nearest * nearest;
  const double variance0 = std::max({variance, nearest2 * kVarianceFloorScale, kMinVariance});
  // With N = S(lambda_e) for the SG emitter (the emission's normalisation otherwise):
  // E S(lambda_s) = P (1 - e^(-2 d^2 / v')) / (N d^2) <= P / N min(1 / d^2,
  // 2 / v'); E itself <= P / (2 pi N v'_0).
  const double perIntegral = power / normalisation;
  const double cap = 2.0 / variance0;
  const double flux = perIntegral * (nearest2 > 0.0 ? std::min(1.0 / nearest2, cap) : cap);
  const double peak = perIntegral / (2.0 * kPi * variance0);

  // The spot's axis lies in the cone of the group's sphere seen from the mean; outside that cone
  // widened by 1 - cos = ln(1 / kTail) / lambda_s, lambda_s >= nearest^2 / v'_0, the spot is
  // below kTail (the whole sphere once the widening reaches 2).
  const double spotSharpness = nearest2 / variance0;
  const double logInverseTail = -std::log(kTail);
  const bool narrow = spotSharpness > 0.5 * logInverseTail;
  double coneAngle = centreDistance > group.radius ? std::asin(group.radius / centreDistance) : kPi;
  coneAngle += (narrow ? std::acos(1.0 - logInverseTail / spotSharpness) : kPi) + kAngleMargin;
  const bool everywhere = coneAngle >= kPi;
  const glm::dvec3 toward = centreDistance > 0.0 ? toLight / centreDistance : -axis;
  const double emission =
      everywhere
          ? 1.0
          : std::exp(sharpness *
                     (std::cos(std::max(angleBetween(toward, -axis) - coneAngle, 0.0)) - 1.0));
  const double cosine =
      everywhere
          ? 1.0
          : std::max(
                std::cos(std::max(
                    angleBetween(toward, group.normalAxis) - coneAngle - group.normalAngle, 0.0)),
                0.0);
  const double tail = everywhere ? 0.0 : kTail;

  VsglLobeBound b;
  b.diffuse = flux * (group.albedo / kPi) * (emission * cosine + tail);
  // Glossy, the smaller of: f_spec (w . n) <= F / (2 pi alpha^2 (n.v + sqrt(alpha^2 + (1 -
  // alpha^2) n.v^2))) over the same directions (vsgl_bound.glsl), or the largest incoming
  // radiance times the specular albedo.
  const double a2 = group.alpha * group.alpha, nv = group.viewCosine;
  const double peakBrdf =
      group.fresnel / (2.0 * kPi * a2 * (nv + std::sqrt(a2 + (1.0 - a2) * nv * nv)));
  const double above = cosine > 0.0 ? 1.0 : 0.0;
  const double sharpGlossy = flux * (emission * above + tail) * peakBrdf;
  const double wideGlossy = peak * std::max(emission, tail) * group.specularAlbedo * kAlbedoMargin;
  b.glossy = std::min(sharpGlossy, wideGlossy);
  return b;
}

}  // namespace gi
