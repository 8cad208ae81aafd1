// The numerical-stability suite on the CPU reference, for the two cases of vsgl-math.md section
// 12 whose other tests are GPU-only (docs/techniques/stability.md): non-finite RSM texels
// (case 14) and a huge dynamic range far from the RSM origin (case 5), run through the double
// twins of the attributes pass and of filtered sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "reference/vsgl_attributes_reference.h"
#include "reference/vsgl_sampling.h"
#include "shared/vsgl.h"

namespace {

bool finite(const glm::dvec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// Case 14: an RSM texel with a NaN flux, one with an infinite position and one with a NaN
// roughness contribute nothing (every attribute exactly 0), and the one clean texel keeps its
// power; no attribute anywhere is non-finite.
TEST(StabilityReference, NonFiniteRsmTexelsAreMasked) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  gi::RsmImages rsm;
  rsm.position = {{0.1f, -0.2f, -1.0f, 1.0f},
                  {0.0f, 0.0f, -1.0f, 1.0f},
                  {inf, 0.0f, -1.0f, 1.0f},
                  {0.2f, 0.1f, -1.2f, 1.0f}};
  rsm.diffuse = {{0.5f, 0.4f, 0.3f, 1.0f},
                 {nan, 0.4f, 0.3f, 1.0f},
                 {0.5f, 0.4f, 0.3f, 1.0f},
                 {0.5f, 0.4f, 0.3f, 1.0f}};
  rsm.specular = {{0.04f, 0.04f, 0.04f, 0.5f},
                  {0.04f, 0.04f, 0.04f, 0.5f},
                  {0.04f, 0.04f, 0.04f, 0.5f},
                  {0.04f, 0.04f, 0.04f, nan}};
  rsm.surface.width = 2;
  rsm.surface.height = 2;
  rsm.surface.samples.resize(4);
  for (auto& s : rsm.surface.samples) s.normal = glm::dvec3(0.0, 0.0, 1.0);
  const auto attributes = gi::vsglAttributesReference(rsm, gi::RsmView{});
  for (int a = 0; a < VSGL_ATTR_COUNT; ++a)
    for (size_t t = 0; t < 4; ++t) {
      EXPECT_TRUE(finite(attributes[a][t])) << "attribute " << a << " texel " << t;
      if (t > 0) {
        EXPECT_EQ(attributes[a][t], glm::dvec4(0.0)) << "attribute " << a << " texel " << t;
      }
    }
  EXPECT_EQ(glm::dvec3(attributes[VSGL_ATTR_DIFFUSE_POWER][0]),
            glm::dvec3(glm::vec3(0.5f, 0.4f, 0.3f)));
  EXPECT_GT(attributes[VSGL_ATTR_DIFFUSE_POWER][0].w, 0.0);
}

// Case 5: powers from 1e-3 to 4e6 W at 141-500 m from the RSM origin (w |y|^2 ~ 1e12). In double
// every VSGL is finite, the total power is kept within 2 % (case 2's bound for modified FIS),
// variances are non-negative and means lie inside the lit patch (to the fp32 rounding of the
// record's 500 m coordinates).
TEST(StabilityReference, HugeDynamicRangeFarFromTheOrigin) {
  const uint32_t size = 64;
  const glm::dvec3 offset(300.0, -200.0, 400.0);
  std::array<std::vector<glm::dvec4>, VSGL_ATTR_COUNT> base;
  for (auto& b : base) b.assign(size_t{size} * size, glm::dvec4(0.0));
  std::vector<double> pdf(size_t{size} * size);
  double total = 0.0;
  for (uint32_t t = 0; t < pdf.size(); ++t) {
    const double w =
        std::pow(10.0, -3.0 + 9.6 * double((t * 37) % pdf.size()) / double(pdf.size()));
    const glm::dvec3 y = offset + glm::dvec3((t % size + 0.5) / size, (t / size + 0.5) / size, 1.0);
    base[VSGL_ATTR_DIFFUSE_POWER][t] = glm::dvec4(w, w, w, w);
    base[VSGL_ATTR_DIFFUSE_POSITION][t] = glm::dvec4(w * y, w * glm::dot(y, y));
    base[VSGL_ATTR_DIFFUSE_AXIS][t] = glm::dvec4(0.0, 0.0, w * VSGL_DIFFUSE_LOBE_LENGTH, w);
    pdf[t] = w;
    total += w;
  }
  std::array<gi::VectorPyramid, VSGL_ATTR_COUNT> pyramids;
  for (int a = 0; a < VSGL_ATTR_COUNT; ++a) pyramids[a] = gi::makeVectorPyramid(base[a], size);
  const uint32_t n = 256;
  const auto v = gi::generateVsglsReference(pyramids, gi::makeScalarPyramid(pdf, size),
                                            glm::dvec3(0.0), n, 1.0, VSGL_RULE_MODIFIED);
  double sum = 0.0;
  const double slack = 500.0 * 0x1p-24;  // the record is fp32
  for (uint32_t i = 0; i < n; ++i) {
    const gpu::VsglLobe& d = v[i].diffuse;
    EXPECT_TRUE(std::isfinite(d.meanVariance.w) && std::isfinite(d.power.w)) << "VSGL " << i;
    EXPECT_GE(d.meanVariance.w, 0.0f) << "VSGL " << i;
    sum += d.power.g;
    if (!(d.power.w > 0.0f)) continue;
    for (int c = 0; c < 3; ++c) {
      const double lo = offset[c] + (c == 2 ? 1.0 : 0.0), hi = offset[c] + 1.0;
      EXPECT_GE(d.meanVariance[c], lo - slack) << "VSGL " << i << " axis " << c;
      EXPECT_LE(d.meanVariance[c], hi + slack) << "VSGL " << i << " axis " << c;
    }
  }
  EXPECT_NEAR(sum, total, 0.02 * total);
}

}  // namespace
