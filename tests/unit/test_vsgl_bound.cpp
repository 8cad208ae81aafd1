// The VSGL culling bound (reference/vsgl_bound.h, the twin of shaders/common/vsgl_bound.glsl)
// held against the shading it bounds: for groups of receivers of every kind (points and wide
// tiles, flat and curved, rough and mirror-like, metals and dielectrics) and lobes of every
// kind (zero and wide variance, isotropic to sharp emission, receivers at the mean), no
// receiver's diffuse or glossy light from a lobe (reference/vsgl_shade_reference.h, the model
// the GPU shades) exceeds the lobe's bound over its group.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "lcg.h"
#include "reference/vsgl_bound.h"
#include "reference/vsgl_shade_reference.h"
#include "test_vsgls.h"

namespace {

using testing_common::Lcg;

glm::dvec3 unitVector(Lcg& rng) {
  const double z = 2.0 * rng.next() - 1.0, phi = 6.283185307179586 * rng.next();
  const double s = std::sqrt(std::max(1.0 - z * z, 0.0));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// A unit vector at an angle uniform in [0, angle] from `axis`, in a random direction.
glm::dvec3 perturbed(glm::dvec3 axis, double angle, Lcg& rng) {
  glm::dvec3 t = unitVector(rng);
  t -= axis * glm::dot(t, axis);
  if (glm::dot(t, t) < 1e-12) t = glm::cross(axis, glm::dvec3(1.0, 0.0, 0.0));
  if (glm::dot(t, t) < 1e-12) t = glm::cross(axis, glm::dvec3(0.0, 1.0, 0.0));
  const double a = angle * rng.next();
  return glm::normalize(std::cos(a) * axis + std::sin(a) * glm::normalize(t));
}

double largest(glm::dvec3 c) {
  return std::max({c.r, c.g, c.b});
}

// The light of one lobe at one receiver: the VSGL holds it as its diffuse lobe and nothing else
// (so that, with planar emitters, the lobe also sets the VSGL's plane).
gpu::Vsgl onlyLobe(const gpu::VsglLobe& lobe) {
  gpu::Vsgl v{};
  v.diffuse = lobe;
  return v;
}

gi::IndirectRadiance lobeLight(const gi::ShadeReceiver& at, const gpu::VsglLobe& lobe,
                               bool planar = false) {
  const gpu::Vsgl v = onlyLobe(lobe);
  return gi::shadeReference(at, std::span<const gpu::Vsgl>(&v, 1), true, planar);
}

// Groups of eight receivers and sixteen lobes from a fixed-seed LCG: 400 groups, 51 200 pairs,
// with the SG emitter and with planar emitters (docs/techniques/planar-emitters.md). The bound
// is exact arithmetic on the same double model, so it may not be exceeded at all: the only
// slack is 1e-9 relative for the rounding of the two computations.
class VsglBoundModels : public testing::TestWithParam<bool> {};

TEST_P(VsglBoundModels, NoReceiverGetsMoreThanTheBound) {
  const bool planar = GetParam();
  Lcg rng(20261202);
  const double extents[] = {0.0, 0.01, 0.1, 0.5};
  const double spreads[] = {0.0, 0.1, 0.5, 1.5};
  const double roughnesses[] = {0.03, 0.2, 0.5, 1.0};
  size_t pairs = 0, lit = 0, exceeded = 0;
  std::vector<double> diffuseRatios, glossyRatios;  // light / bound, where there is light
  for (int g = 0; g < 400; ++g) {
    const glm::dvec3 base(2.0 * rng.next() - 1.0, 2.0 * rng.next() - 1.0, 2.0 * rng.next() - 1.0);
    const glm::dvec3 normal = unitVector(rng);
    const double extent = extents[g % 4], spread = spreads[(g / 4) % 4];
    std::vector<gi::ShadeReceiver> receivers(8);
    for (gi::ShadeReceiver& r : receivers) {
      r.position = base + extent * glm::dvec3(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
      r.normal = perturbed(normal, spread, rng);
      r.view = perturbed(r.normal, 1.5, rng);
      r.albedo = {rng.next(), rng.next(), rng.next()};
      const bool metal = rng.next() < 0.3;
      r.f0 = metal ? glm::dvec3(rng.next(), rng.next(), rng.next()) : glm::dvec3(0.04);
      r.f90 = metal ? 1.0 : (g % 3 == 0 ? 0.0 : 1.0);
      r.roughness = roughnesses[(g / 16) % 4] * (0.5 + rng.next());
    }
    const gi::VsglReceivers group = gi::vsglReceivers(receivers, true);
    for (int k = 0; k < 16; ++k) {
      // Means anywhere, near the group, or at a receiver; variances from 0 to 1 m^2.
      glm::dvec3 mean(2.0 * rng.next() - 1.0, 2.0 * rng.next() - 1.0, 2.0 * rng.next() - 1.0);
      if (k % 4 == 1) mean = base + 0.05 * unitVector(rng);
      if (k % 8 == 3) mean = receivers[k % 8].position;
      const double variance = k % 5 == 0 ? 0.0 : std::pow(10.0, -6.0 + 6.0 * rng.next());
      const double sharpness =
          k % 3 == 0 ? 2.2925 : (k % 3 == 1 ? 0.0 : std::pow(10.0, 4.0 * rng.next()));
      const gpu::VsglLobe lobe = testing_gpu::vsglLobe(
          glm::vec3(mean), float(variance), glm::vec3(unitVector(rng)), float(sharpness),
          glm::vec3(rng.next(), rng.next(), rng.next()) * 10.0f);
      const gi::VsglLobeBound bound =
          gi::vsglLobeBound(lobe, group, gi::vsglEmission(onlyLobe(lobe), planar).diffuse);
      for (const gi::ShadeReceiver& r : receivers) {
        const gi::IndirectRadiance light = lobeLight(r, lobe, planar);
        const double diffuse = largest(light.diffuse), glossy = largest(light.glossy);
        ++pairs;
        const bool over =
            diffuse > bound.diffuse * (1.0 + 1e-9) || glossy > bound.glossy * (1.0 + 1e-9);
        if (over && exceeded++ < 5)
          ADD_FAILURE() << "group " << g << " lobe " << k << ": diffuse " << diffuse << " (bound "
                        << bound.diffuse << "), glossy " << glossy << " (bound " << bound.glossy
                        << ")";
        if (diffuse > 0.0) diffuseRatios.push_back(diffuse / bound.diffuse);
        if (glossy > 0.0) glossyRatios.push_back(glossy / bound.glossy);
        lit += diffuse > 0.0;
      }
    }
  }
  EXPECT_EQ(exceeded, 0u) << "of " << pairs << " pairs";
  ASSERT_GT(lit, pairs / 2) << "the cases must mostly be lit";
  // How tight the bound is: printed for docs/techniques/vsgl-culling.md.
  for (std::vector<double>* ratios : {&diffuseRatios, &glossyRatios}) {
    std::sort(ratios->begin(), ratios->end());
    std::printf("%s light / bound over %zu lit pairs: median %.3g, 90th percentile %.3g\n",
                ratios == &diffuseRatios ? "diffuse" : "glossy", ratios->size(),
                (*ratios)[ratios->size() / 2], (*ratios)[ratios->size() * 9 / 10]);
  }
}

INSTANTIATE_TEST_SUITE_P(Emitters, VsglBoundModels, testing::Bool(),
                         [](const testing::TestParamInfo<bool>& param) {
                           return param.param ? "Planar" : "Sg";
                         });

// The bound sees what culls: the same lobe turned away from a tile, or moved 20 times farther,
// is bounded far below the lobe facing it (a bound that ignored direction or distance would
// cull nothing).
TEST(VsglBound, FallsWithDistanceAndFacing) {
  std::vector<gi::ShadeReceiver> tile(4);
  for (int i = 0; i < 4; ++i) {
    tile[i].position = {0.05 * (i % 2), 0.0, 0.05 * (i / 2)};
    tile[i].normal = {0.0, 1.0, 0.0};
    tile[i].albedo = glm::dvec3(0.8);
    tile[i].f0 = glm::dvec3(0.04);
    tile[i].roughness = 0.6;
  }
  const gi::VsglReceivers group = gi::vsglReceivers(tile, true);
  auto bound = [&](glm::vec3 mean, glm::vec3 axis) {
    const gi::VsglLobeBound b = gi::vsglLobeBound(
        testing_gpu::vsglLobe(mean, 1e-3f, axis, 2.2925f, glm::vec3(1.0f)), group);
    return b.diffuse + b.glossy;
  };
  const double facing = bound({0.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
  EXPECT_GT(facing, 0.0);
  EXPECT_LT(bound({0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}), 0.05 * facing);  // e^(-2 x 2.29) = 0.01
  EXPECT_LT(bound({0.0f, 20.0f, 0.0f}, {0.0f, -1.0f, 0.0f}),
            0.004 * facing);                                                 // 1 / 400 (+ the tile)
  EXPECT_LT(bound({0.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}), 1e-3 * facing);  // below the horizon
}

}  // namespace
