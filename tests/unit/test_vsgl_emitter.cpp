// Planar emitters (gi/src/reference/vsgl_emitter.h, docs/techniques/planar-emitters.md): what a
// flat cluster must and must not light, and that the cut keeps its power. The shading twin is
// compared with the GPU in tests/gpu/test_vsgl_shade.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "reference/vsgl_emitter.h"
#include "reference/vsgl_shade_reference.h"
#include "test_vsgls.h"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kVariance = 1e-2;  // sigma = 0.1 m
const glm::dvec3 kUp(0.0, 1.0, 0.0);

// A flat cluster at the origin in the plane y = 0, facing +y: one texel's diffuse sharpness
// (beta = 1), white diffuse power 1 W, and a glossy lobe of 0.5 W leaving at 53 degrees.
gpu::Vsgl flatVsgl(float diffuseSharpness = float(VSGL_FLAT_SHARPNESS)) {
  gpu::Vsgl v{};
  v.diffuse = testing_gpu::vsglLobe({0, 0, 0}, float(kVariance), {0, 1, 0}, diffuseSharpness,
                                    glm::vec3(1.0f));
  v.specular = testing_gpu::vsglLobe({0, 0, 0}, float(kVariance), {0.6f, 0.8f, 0.0f}, 50.0f,
                                     glm::vec3(0.5f));
  return v;
}

gpu::Vsgl withoutSpecular(gpu::Vsgl v) {
  v.specular.power = glm::vec4(0.0f);
  return v;
}

gpu::Vsgl withoutDiffuseLight(gpu::Vsgl v) {
  v.diffuse.power.r = v.diffuse.power.g = v.diffuse.power.b = 0.0f;  // keeps the plane (power.a)
  return v;
}

gi::ShadeReceiver receiverAt(glm::dvec3 position, glm::dvec3 normal) {
  gi::ShadeReceiver r;
  r.position = position;
  r.normal = glm::normalize(normal);
  r.view = r.normal;
  r.albedo = glm::dvec3(1.0);
  r.f0 = glm::dvec3(0.04);
  r.roughness = 0.5;
  return r;
}

// Diffuse irradiance (W/m^2) and glossy radiance the VSGL gives the receiver: the diffuse output
// is albedo / pi times the irradiance.
struct Light {
  double irradiance = 0.0;
  double glossy = 0.0;
};

Light light(const gpu::Vsgl& v, const gi::ShadeReceiver& r, bool planar) {
  const gi::IndirectRadiance out =
      gi::shadeReference(r, std::span<const gpu::Vsgl>(&v, 1), true, planar);
  return {kPi * out.diffuse.r, out.glossy.r};
}

}  // namespace

TEST(VsglEmitter, PlanarityIsSmoothFromCornerToFlat) {
  EXPECT_EQ(gi::vsglPlanarity(0.0), 0.0);
  EXPECT_EQ(gi::vsglPlanarity(VSGL_CORNER_SHARPNESS), 0.0);
  EXPECT_EQ(gi::vsglPlanarity(VSGL_FLAT_SHARPNESS), 1.0);
  EXPECT_EQ(gi::vsglPlanarity(3.0), 1.0);
  double previous = 0.0;
  const double step = (VSGL_FLAT_SHARPNESS - VSGL_CORNER_SHARPNESS) / 1000.0;
  for (int i = 1; i <= 1000; ++i) {
    const double beta = gi::vsglPlanarity(VSGL_CORNER_SHARPNESS + i * step);
    EXPECT_GE(beta, previous);
    // smoothstep's slope is at most 1.5 per unit of t: no jump that could flicker.
    EXPECT_LE(beta - previous, 1.5e-3 + 1e-12);
    previous = beta;
  }
  // The flat sharpness is one texel's: Banerjee's estimate at the diffuse lobe's mean length.
  const double r = VSGL_DIFFUSE_LOBE_LENGTH;
  EXPECT_NEAR(r * (3.0 - r * r) / (1.0 - r * r), VSGL_FLAT_SHARPNESS, 1e-6);
  const double corner = r / std::sqrt(2.0);
  EXPECT_NEAR(corner * (3.0 - corner * corner) / (1.0 - corner * corner), VSGL_CORNER_SHARPNESS,
              1e-12);
}

// A floor does not light itself: receivers in the cluster's plane, facing its way, get nothing,
// at the mean, inside the cluster and far from it. The SG emitter leaks there (the test bites).
TEST(VsglEmitter, CoplanarReceiverGetsNothing) {
  const gpu::Vsgl v = flatVsgl();
  for (double d : {0.0, 0.01, 0.1, 0.3, 1.0, 10.0}) {
    SCOPED_TRACE("distance " + std::to_string(d));
    const gi::ShadeReceiver r = receiverAt({d * 0.8, 0.0, d * 0.6}, kUp);
    const Light planar = light(v, r, true);
    EXPECT_EQ(planar.irradiance, 0.0);
    EXPECT_EQ(planar.glossy, 0.0);
    if (d > 0.0 && d <= 1.0) {
      EXPECT_GT(light(v, r, false).irradiance, 0.0) << "the SG emitter leaks here";
    }
  }
}

// Positions carry rounding: a receiver a hair above or below the plane (1e-4 sigma, more than
// fp32 depth leaves on a 10 m scene) still gets at most 1e-3 of what the same point would get
// facing the cluster.
TEST(VsglEmitter, NearlyCoplanarReceiverGetsAlmostNothing) {
  const gpu::Vsgl v = withoutSpecular(flatVsgl());
  for (double d : {0.0, 0.02, 0.1, 0.3, 1.0})
    for (double h : {-1e-5, 1e-5}) {
      SCOPED_TRACE("distance " + std::to_string(d) + ", height " + std::to_string(h));
      const glm::dvec3 p(d, h, 0.0);
      const double coplanar = light(v, receiverAt(p, kUp), true).irradiance;
      const double facing =
          light(v, receiverAt(p + glm::dvec3(0.0, 0.05, 0.0), -kUp), true).irradiance;
      ASSERT_GT(facing, 0.0);
      EXPECT_LE(coplanar, 1e-3 * facing);
    }
}

// A wall's outer face does not light the room behind it: every receiver behind the cluster's
// plane, whichever way it faces, gets nothing; the SG emitter leaks there.
TEST(VsglEmitter, BackFaceLightsNothingBehindItsPlane) {
  const gpu::Vsgl v = flatVsgl();
  size_t leaking = 0;
  for (double depth : {0.001, 0.05, 0.5})
    for (double side : {0.0, 0.1, 1.0})
      for (glm::dvec3 n :
           {glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0), glm::dvec3(1, 0, 0), glm::dvec3(-1, 1, 0)}) {
        const gi::ShadeReceiver r = receiverAt({side, -depth, 0.0}, n);
        const Light planar = light(v, r, true);
        EXPECT_EQ(planar.irradiance, 0.0) << "depth " << depth << " side " << side;
        EXPECT_EQ(planar.glossy, 0.0) << "depth " << depth << " side " << side;
        leaking += light(v, r, false).irradiance > 0.0;
      }
  EXPECT_GT(leaking, 0u) << "the SG emitter leaks behind its plane";
}

// Far away a flat cluster's diffuse lobe is a Lambertian point light: E = Phi cos_e cos_r / (pi
// d^2), here with the receiver facing the mean. Tolerance 1e-3: the spot's width (sigma / d =
// 1e-3) and the [T24] clamped-cosine fit at a sharp lobe.
TEST(VsglEmitter, FarFieldIsLambertian) {
  const gpu::Vsgl v = withoutSpecular(flatVsgl());
  const double d = 100.0;
  for (double c : {1.0, 0.7, 0.3, 0.05}) {
    const glm::dvec3 dir(std::sqrt(1.0 - c * c), c, 0.0);
    const double e = light(v, receiverAt(d * dir, -dir), true).irradiance;
    EXPECT_NEAR(e, c / (kPi * d * d), 1e-3 * c / (kPi * d * d)) << "elevation cosine " << c;
  }
}

// Just above the middle of a flat cluster, facing it, a receiver sees a Lambertian plane of
// exitance Phi p(0) = Phi / (2 pi v): what the cut's normalisation gives, within 1 % (the spot
// is not perfectly wide at h = 1e-3 sigma, and the receiver sees the Gaussian's fall-off).
TEST(VsglEmitter, InsideTheClusterSeesItsExitance) {
  const gpu::Vsgl v = withoutSpecular(flatVsgl());
  const double exitance = 1.0 / (2.0 * kPi * kVariance);
  const double e = light(v, receiverAt({0.0, 1e-4, 0.0}, -kUp), true).irradiance;
  EXPECT_NEAR(e, exitance, 0.01 * exitance);
}

// The cut keeps the lobe's power: the irradiance of receivers on a sphere of radius R around the
// cluster, each facing its centre, adds up to the lobe's power, for a flat cluster, a corner-ish
// one and with the SG emitter. Quadrature: 400 x 800 cells in (cos theta, phi), exact to 1e-5 for
// these lobes at R = 50 sigma. Tolerances: 2e-3 for the diffuse lobe (its N is exact; the
// far-field spot, sigma / R = 2e-3 wide, and the [T24] fit at the receiver), 1e-2 for the
// glossy lobe, whose N itself comes from the [T24] fit (sg-lighting.md: <= 1.6e-3 of 2U).
TEST(VsglEmitter, CutKeepsThePower) {
  const double radius = 5.0;
  const int rows = 400, columns = 800;
  for (float sharpness : {float(VSGL_FLAT_SHARPNESS), 1.9f, 1.0f})
    for (bool planar : {true, false})
      for (bool glossyLobe : {false, true}) {
        const gpu::Vsgl v = glossyLobe ? withoutDiffuseLight(flatVsgl(sharpness))
                                       : withoutSpecular(flatVsgl(sharpness));
        const double power = glossyLobe ? 0.5 : 1.0;
        double total = 0.0;
        for (int i = 0; i < rows; ++i)
          for (int j = 0; j < columns; ++j) {
            const double c = -1.0 + 2.0 * (i + 0.5) / rows;
            const double phi = 2.0 * kPi * (j + 0.5) / columns;
            const double s = std::sqrt(1.0 - c * c);
            const glm::dvec3 dir(s * std::cos(phi), c, s * std::sin(phi));
            const double e = light(v, receiverAt(radius * dir, -dir), planar).irradiance;
            total += e * radius * radius * (2.0 / rows) * (2.0 * kPi / columns);
          }
        std::printf("sharpness %.2f %s %s lobe: power %.6f of %.1f\n", sharpness,
                    planar ? "planar" : "SG", glossyLobe ? "glossy" : "diffuse", total, power);
        EXPECT_NEAR(total, power, (glossyLobe ? 1e-2 : 2e-3) * power)
            << "sharpness " << sharpness << (planar ? " planar" : " SG")
            << (glossyLobe ? " glossy" : " diffuse");
      }
}
