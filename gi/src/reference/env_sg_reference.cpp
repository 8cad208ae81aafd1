#include "reference/env_sg_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/error.h"
#include "reference/env_paraboloid.h"
#include "reference/sg_math.h"

namespace gi {

namespace {

constexpr uint32_t kLayers = 2;
const double kOneBelow = std::nextafter(1.0, 0.0);

// The layer split: the same rule as lattice_warp.glsl's split() (strict u < q, so a layer of
// zero mass is never chosen; an all-zero PDF splits evenly).
uint32_t splitLayer(double& u, double first, double second) {
  const double total = first + second;
  const double q = total > 0.0 ? first / total : 0.5;
  if (u < q) {
    u = std::min(u / q, kOneBelow);
    return 0;
  }
  u = std::min((u - q) / (1.0 - q), kOneBelow);
  return 1;
}

}  // namespace

double envSgLuminance(glm::dvec3 rgb) {
  return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

EnvSgTexelWeight envSgTexelWeight(uint32_t n, uint32_t layer, uint32_t x, uint32_t y) {
  // The points of envMapTexelSolidAngle: 2 st - 1 = (2 (K x + i) + 1 - K n) / (K n), exact.
  const uint32_t k = ENV_SG_TEXEL_SAMPLES;
  const double kn = double(k) * n;
  EnvSgTexelWeight weight;
  for (uint32_t j = 0; j < k; ++j)
    for (uint32_t i = 0; i < k; ++i) {
      const glm::dvec2 c((2.0 * (k * x + i) + 1.0 - kn) / kn, (2.0 * (k * y + j) + 1.0 - kn) / kn);
      const double rho2 = kParaboloidScale * kParaboloidScale * glm::dot(c, c);
      const double onePlusRho2 = 1.0 + rho2;
      const double r = 16.0 * kParaboloidScale * kParaboloidScale / (onePlusRho2 * onePlusRho2);
      weight.fullSolidAngle += r;
      weight.direction += r * paraboloidToDirection(0.5 + 0.5 * c, layer);
      if (layer == 0 ? rho2 > 1.0 : rho2 >= 1.0) continue;  // the other hemisphere's point
      weight.solidAngle += r;
    }
  weight.solidAngle /= kn * kn;
  weight.fullSolidAngle /= kn * kn;
  weight.direction /= kn * kn;
  return weight;
}

double EnvSgPyramids::massTop() const {
  return pyramids[ENV_SG_RADIANCE][0].levels.back()[0].a +
         pyramids[ENV_SG_RADIANCE][1].levels.back()[0].a;
}

EnvSgPyramids envSgPyramids(const EnvMapReference& map) {
  const uint32_t n = map.size;
  if (n == 0 || map.levels.empty()) throw engine::Error("environment SG pyramids: an empty map");
  EnvSgPyramids out;
  out.size = n;
  for (uint32_t layer = 0; layer < kLayers; ++layer) {
    std::vector<glm::dvec4> radiance(size_t{n} * n), direction(size_t{n} * n);
    for (uint32_t y = 0; y < n; ++y)
      for (uint32_t x = 0; x < n; ++x) {
        const EnvSgTexelWeight weight = envSgTexelWeight(n, layer, x, y);
        const glm::dvec3 value = map.texel(0, layer, x, y);
        const double luminance = envSgLuminance(value);
        const size_t i = size_t{y} * n + x;
        radiance[i] = glm::dvec4(weight.fullSolidAngle * value, weight.solidAngle * luminance);
        direction[i] = glm::dvec4(luminance * weight.direction, weight.fullSolidAngle * luminance);
        out.solidAngle += weight.solidAngle;
      }
    out.pyramids[ENV_SG_RADIANCE][layer] = makeVectorPyramid(radiance, n);
    out.pyramids[ENV_SG_DIRECTION][layer] = makeVectorPyramid(direction, n);
    ScalarPyramid& mass = out.mass[layer];
    mass.size = n;
    for (const std::vector<glm::dvec4>& level : out.pyramids[ENV_SG_RADIANCE][layer].levels) {
      std::vector<double>& values = mass.levels.emplace_back(level.size());
      for (size_t i = 0; i < level.size(); ++i) values[i] = level[i].a;
    }
  }
  return out;
}

glm::dvec3 EnvSgLightReference::integral() const {
  return amplitude * sgIntegral(sharpness);
}

EnvSgWarp envSgWarp(const EnvSgPyramids& pyramids, glm::dvec2 u) {
  EnvSgWarp out;
  out.layer = splitLayer(u.x, pyramids.mass[0].levels.back()[0], pyramids.mass[1].levels.back()[0]);
  out.warp = warpHierarchical(pyramids.mass[out.layer], u);
  return out;
}

double envSgKernelMass(const EnvSgPyramids& pyramids, uint32_t layer, glm::dvec2 x, double level) {
  const double top = pyramids.massTop();
  if (!(top > 0.0)) return 0.0;
  const double m = double(pyramids.size) * pyramids.size;
  return std::exp2(2.0 * level) *
         sampleTrilinear(pyramids.pyramids[ENV_SG_DIRECTION][layer], x, level).w / (m * top);
}

double envSgKernelLevel(const EnvSgPyramids& pyramids, uint32_t layer, glm::dvec2 x, uint32_t n,
                        double k, int steps) {
  const double top = pyramids.topLevel();
  const double target = k / n;
  if (!(pyramids.massTop() > 0.0)) return top;
  if (envSgKernelMass(pyramids, layer, x, 0.0) >= target) return 0.0;
  if (k >= n) return top;
  // g(l) grows with l ([S3] after Eq. 2): [lo, hi] keeps g(lo) < K / N <= g(hi) (or hi = L).
  double lo = 0.0, hi = top;
  for (int step = 0; step < steps; ++step) {
    const double mid = 0.5 * (lo + hi);
    (envSgKernelMass(pyramids, layer, x, mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<EnvSgLightReference> generateEnvSgLightsReference(const EnvSgPyramids& pyramids,
                                                              uint32_t n, double k) {
  const double massTop = pyramids.massTop();
  const double m = double(pyramids.size) * pyramids.size;
  const double solidAngleScale = 4.0 * std::numbers::pi / pyramids.solidAngle;
  std::vector<EnvSgLightReference> lights(n);
  for (uint32_t i = 0; i < n; ++i) {
    EnvSgLightReference& light = lights[i];
    const EnvSgWarp warp = envSgWarp(pyramids, fibonacciPoint(i, n));
    light.layer = warp.layer;
    light.x = warp.warp.x;
    light.texel[0] = warp.warp.texel.x;
    light.texel[1] = warp.warp.texel.y;
    light.level = envSgKernelLevel(pyramids, warp.layer, warp.warp.x, n, k);
    const glm::dvec4 radiance =
        sampleTrilinear(pyramids.pyramids[ENV_SG_RADIANCE][warp.layer], light.x, light.level);
    const glm::dvec4 direction =
        sampleTrilinear(pyramids.pyramids[ENV_SG_DIRECTION][warp.layer], light.x, light.level);
    if (!(massTop > 0.0) || !(radiance.a > 0.0) || !(direction.w > 0.0)) continue;  // zero
    // The axis: the sample's own direction, which the lattice and the warp distribute by the
    // PDF. The kernel's mean direction would lean toward the layer's pole (a square kernel in
    // paraboloid space covers more solid angle on its pole side). The sharpness: Banerjee's,
    // from the length of the kernel's luminance-weighted mean direction (its spread).
    const double meanLength = glm::length(glm::dvec3(direction) / direction.w);
    if (meanLength > 0.0) {
      light.axis = paraboloidToDirection(light.x, warp.layer);
      light.sharpness = banerjeeSharpness(meanLength);
    }
    // Phi = (sum m / N) rgb~ / m~, rescaled to 4 pi of solid angle, spread over S(sharpness).
    const glm::dvec3 phi = (m * massTop / n) * (glm::dvec3(radiance) / direction.w);
    light.amplitude = phi * solidAngleScale / sgIntegral(light.sharpness);
    light.density = 2.0 * radiance.a / massTop;
  }
  return lights;
}

EnvShading envSgShade(const EnvFisReceiver& receiver,
                      const std::vector<EnvSgLightReference>& lights) {
  const SgGgxReceiver ggx =
      sgGgxReceiver(receiver.normal, receiver.view, envFisGgxAlpha(receiver.roughness), receiver.f0,
                    receiver.f90);
  EnvShading out;
  for (const EnvSgLightReference& light : lights) {
    if (light.amplitude == glm::dvec3(0.0)) continue;
    Sg sg;
    sg.axis = light.axis;
    sg.sharpness = light.sharpness;
    out.diffuse += light.amplitude * sgClampedCosineIntegralOverPi(
                                         light.sharpness, glm::dot(light.axis, receiver.normal));
    out.glossy += light.amplitude * sgGgxReflection(sg, ggx);
  }
  out.diffuse *= receiver.albedo;
  return out;
}

}  // namespace gi
