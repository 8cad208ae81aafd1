// Broad reflections join the diffuse lobe (docs/techniques/vsgl-generation.md, "Broad
// reflections"): the share of a VPL's glossy power that the glossy lobe keeps, and the attribute
// pass's twin routing the rest into the diffuse lobe without losing power or moving the PDF.
// The GPU pass is compared with the twin in tests/gpu/test_vsgl_generation.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/rsm_reference.h"
#include "reference/vsgl_attributes_reference.h"
#include "reference/vsgl_sampling.h"
#include "shared/vsgl.h"

namespace {

constexpr double kFlat = VSGL_FLAT_SHARPNESS;
constexpr double kGlossy = VSGL_FLAT_SHARPNESS * VSGL_GLOSSY_SHARPNESS_RATIO;

// All of a reflection no narrower than the Lambert lobe goes to the diffuse lobe, all of one
// half its angular width or narrower stays glossy, and the share rises smoothly between: on a
// grid of 4000 steps in log sharpness no step moves it by more than 3 / 2 times the step over
// the range (the smoothstep's steepest slope), so no VPL jumps between lobes as its
// sharpness changes.
TEST(BroadReflections, GlossyShareRisesSmoothlyFromLambertToHalfItsWidth) {
  for (double s : {0.0, 1e-6, 0.5, 1.0, kFlat}) EXPECT_EQ(gi::glossyShare(s), 0.0) << s;
  for (double s : {kGlossy, 2.0 * kGlossy, 5e4, double(VSGL_MAX_SHARPNESS)})
    EXPECT_EQ(gi::glossyShare(s), 1.0) << s;
  const int steps = 4000;
  double previous = 0.0;
  for (int i = 1; i <= steps; ++i) {
    const double s = kFlat * std::pow(double(VSGL_GLOSSY_SHARPNESS_RATIO), double(i) / steps);
    const double share = gi::glossyShare(s);
    EXPECT_GE(share, previous) << "sharpness " << s;
    EXPECT_LE(share - previous, 1.5 / steps + 1e-12) << "sharpness " << s;
    previous = share;
  }
  EXPECT_NEAR(previous, 1.0, 1e-12);
}

// One lit texel facing the light along -z, with a white diffuse flux and a glossy flux of
// roughness `roughness`.
gi::RsmImages texel(float roughness) {
  gi::RsmImages rsm;
  rsm.position = {{0.0f, 0.0f, -2.0f, 1.0f}};
  rsm.diffuse = {{0.3f, 0.2f, 0.1f, 1.0f}};
  rsm.specular = {{0.05f, 0.06f, 0.07f, roughness}};
  rsm.surface.width = rsm.surface.height = 1;
  rsm.surface.samples.resize(1);
  rsm.surface.samples[0].normal = glm::dvec3(0.0, 0.6, 0.8);
  return rsm;
}

// The twin routes a rough texel's glossy power into the diffuse lobe and keeps a polished
// texel's glossy; between, it shares it. Either way the two lobes carry the texel's whole
// power (to double rounding) and the PDF (the diffuse axis map's alpha) is the texel's whole
// luminance, so importance sampling does not change; the diffuse lobe's axis stays the normal
// with the Lambert lobe's mean length, so the planarity read from it does not change either.
TEST(BroadReflections, AttributesRouteBroadReflectionsIntoTheDiffuseLobe) {
  for (float roughness : {0.95f, 0.6f, 0.55f, 0.1f}) {
    SCOPED_TRACE("roughness " + std::to_string(roughness));
    const gi::RsmImages rsm = texel(roughness);
    const auto a = gi::vsglAttributesReference(rsm, gi::RsmView{}, true);
    const glm::dvec3 d(rsm.diffuse[0]), s(rsm.specular[0]);
    const glm::dvec3 toLight = -glm::normalize(glm::dvec3(rsm.position[0]));
    const double share = gi::glossyShare(
        gi::specularLobe(rsm.surface.samples[0].normal, toLight, roughness).sharpness);
    const glm::dvec4 diffusePower = a[VSGL_ATTR_DIFFUSE_POWER][0];
    const glm::dvec4 specularPower = a[VSGL_ATTR_SPECULAR_POWER][0];
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(specularPower[k], share * s[k], 1e-15);
      EXPECT_NEAR(diffusePower[k] + specularPower[k], d[k] + s[k], 1e-15);
    }
    EXPECT_NEAR(a[VSGL_ATTR_DIFFUSE_AXIS][0].w, gi::luminance709(d) + gi::luminance709(s), 1e-15);
    const glm::dvec3 axis = glm::dvec3(a[VSGL_ATTR_DIFFUSE_AXIS][0]) / diffusePower.w;
    EXPECT_NEAR(glm::length(axis), VSGL_DIFFUSE_LOBE_LENGTH, 1e-12);
    EXPECT_GT(glm::dot(axis, rsm.surface.samples[0].normal), VSGL_DIFFUSE_LOBE_LENGTH - 1e-12);
    if (roughness > 0.9f) EXPECT_EQ(specularPower.w, 0.0) << "a matte texel keeps no glossy lobe";
    if (roughness < 0.2f) EXPECT_EQ(specularPower, glm::dvec4(s, gi::luminance709(s)));
    if (roughness == 0.6f || roughness == 0.55f) {
      EXPECT_GT(share, 0.0);
      EXPECT_LT(share, 1.0);
    }
  }
}

// Settings::broadReflections off keeps every reflection in the glossy lobe, the texel's
// diffuse flux alone in the diffuse lobe: the attributes as they were before the split.
TEST(BroadReflections, OffKeepsEveryReflectionGlossy) {
  for (float roughness : {0.95f, 0.6f, 0.1f}) {
    SCOPED_TRACE("roughness " + std::to_string(roughness));
    const gi::RsmImages rsm = texel(roughness);
    const auto a = gi::vsglAttributesReference(rsm, gi::RsmView{}, false);
    const glm::dvec3 d(rsm.diffuse[0]), s(rsm.specular[0]);
    EXPECT_EQ(a[VSGL_ATTR_DIFFUSE_POWER][0], glm::dvec4(d, gi::luminance709(d)));
    EXPECT_EQ(a[VSGL_ATTR_SPECULAR_POWER][0], glm::dvec4(s, gi::luminance709(s)));
    EXPECT_NEAR(a[VSGL_ATTR_DIFFUSE_AXIS][0].w, gi::luminance709(d) + gi::luminance709(s), 1e-15);
  }
}

}  // namespace
