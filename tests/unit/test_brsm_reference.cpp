// The CPU twin of BRSM stage B against closed forms: the importance a cell lobe reflects from a
// far, point-like importance lobe is the reciprocal point-to-point transfer
// Phi_k vMF_k(-l) vMF_c(l) / d^2 (vsgl-math.md sections 4.1 and 7), zero-power lobes add
// nothing, and a singular configuration is clamped, not infinite.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/brsm_reference.h"
#include "reference/sg_math.h"
#include "shared/brsm.h"

namespace {

double vmf(glm::dvec3 direction, const gi::SgLobe& lobe) {
  return gi::sgEvaluate(direction, lobe.axis, lobe.sharpness) / gi::sgIntegral(lobe.sharpness);
}

gpu::Vsgl importanceVsgl(glm::dvec3 mean, double variance, const gi::SgLobe& lobe, double power) {
  gpu::Vsgl v{};
  v.diffuse.meanVariance = glm::vec4(glm::vec3(mean), float(variance));
  v.diffuse.axisSharpness = glm::vec4(glm::vec3(lobe.axis), float(lobe.sharpness));
  v.diffuse.power = glm::vec4(glm::vec3(0.5f), float(power));  // only alpha (the weight) counts
  return v;
}

// With v / d^2 = 2.5e-9 the positional spot is a near delta (sharpness 4e8), so the SG product
// approximates the point transfer to O(lambda / 4e8) ~ 1e-7; 1e-5 leaves room for the fp32
// storage of the record (axes and mean rounded to ~6e-8 relative).
TEST(BrsmReference, FarPointImportanceIsTheReciprocalPointTransfer) {
  const glm::dvec3 receiver(0.3, -0.2, 0.1);
  const glm::dvec3 mean(1.1, 1.5, -0.9);
  const double d = glm::length(mean - receiver);
  const glm::dvec3 toCamera = (mean - receiver) / d;
  for (double cameraSharpness : {0.0, 2.2925, 40.0})
    for (double cellSharpness : {0.0, 2.2925, 15.0}) {
      // Axes near (but not on) the line between the two, so both vMFs are read off-peak.
      const gi::SgLobe camera{glm::normalize(-toCamera + glm::dvec3(0.2, 0.0, 0.1)),
                              cameraSharpness};
      const gi::SgLobe cell{glm::normalize(toCamera + glm::dvec3(0.0, 0.15, -0.1)), cellSharpness};
      const double power = 3.0;
      const gpu::Vsgl v = importanceVsgl(mean, 2.5e-9 * d * d, camera, power);
      const gi::SgLobe cameraStored{glm::dvec3(v.diffuse.axisSharpness), cameraSharpness};
      const double expected = power * vmf(-toCamera, cameraStored) * vmf(toCamera, cell) / (d * d);
      const double got = gi::reflectedImportance({v}, receiver, cell);
      EXPECT_NEAR(got, expected, 1e-5 * expected)
          << "camera sharpness " << cameraSharpness << ", cell sharpness " << cellSharpness;
    }
}

TEST(BrsmReference, LobesWithoutPowerAddNothingAndLobesAdd) {
  const glm::dvec3 receiver(0.0);
  const gi::SgLobe cell{{0.0, 1.0, 0.0}, 2.2925};
  const gi::SgLobe camera{{0.0, -1.0, 0.0}, 5.0};
  const gpu::Vsgl a = importanceVsgl({0.0, 2.0, 0.0}, 0.01, camera, 1.0);
  const gpu::Vsgl b = importanceVsgl({0.5, 2.0, 0.0}, 0.02, camera, 2.0);
  gpu::Vsgl none = importanceVsgl({0.0, 1.0, 0.0}, 0.01, camera, 0.0);
  none.specular = none.diffuse;
  const double ia = gi::reflectedImportance({a}, receiver, cell);
  const double ib = gi::reflectedImportance({b}, receiver, cell);
  EXPECT_GT(ia, 0.0);
  EXPECT_EQ(gi::reflectedImportance({none}, receiver, cell), 0.0);
  EXPECT_NEAR(gi::reflectedImportance({a, none, b}, receiver, cell), ia + ib, 1e-14 * (ia + ib));
}

// A zero-variance lobe exactly at the receiver is a point singularity (section 12, case 12):
// the variance floor keeps it finite, the importance clamp keeps it within fp32.
TEST(BrsmReference, ReceiverAtAZeroVarianceLobeIsClamped) {
  const glm::dvec3 receiver(0.25, 0.5, -1.0);
  const gpu::Vsgl v = importanceVsgl(receiver, 0.0, {{0.0, 0.0, 1.0}, 1e6}, 10.0);
  const double got = gi::reflectedImportance({v}, receiver, {{0.0, 0.0, -1.0}, 1e6});
  EXPECT_TRUE(std::isfinite(got));
  EXPECT_EQ(got, double(BRSM_MAX_IMPORTANCE));
}

}  // namespace
