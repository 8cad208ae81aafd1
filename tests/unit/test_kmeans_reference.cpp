// The CPU reference of the k-means baseline (gi/src/reference/kmeans_reference.h) tested as an
// algorithm: Lloyd's cost never increases, no cluster stays empty, the clusters hold all of the
// RSM's power, the empty-cluster rule does what it states, seeds follow the PDF, and one cluster
// is the filtered path's top-level VSGL.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "kmeans_cases.h"
#include "lcg.h"
#include "reference/kmeans_reference.h"
#include "reference/rsm_reference.h"
#include "reference/vsgl_sampling.h"

namespace gi {
namespace {

constexpr uint32_t kSize = 32;
using testing_common::kKmeansCases;
using testing_common::Lcg;

// Attribute texels of a lit disc (radius 0.45 of the map) folded over a floor (lower half of the
// map, y = 0) and a wall (upper half, z = -1), 4 m from the origin: random powers over a 1:100
// range, random roughness-like specular axes, and a PDF = 0.9 luminance + noise.
AttributeTexels litDisc(uint64_t seed) {
  AttributeTexels t;
  for (auto& a : t) a.assign(size_t{kSize} * kSize, glm::dvec4(0.0));
  Lcg random(seed);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const glm::dvec2 uv((x + 0.5) / kSize - 0.5, (y + 0.5) / kSize - 0.5);
      if (glm::length(uv) > 0.45) continue;
      const size_t i = size_t{y} * kSize + x;
      const bool floor = y < kSize / 2;
      const glm::dvec3 p =
          floor ? glm::dvec3(4.0 + uv.x, 0.0, uv.y) : glm::dvec3(4.0 + uv.x, uv.y, -1.0);
      const glm::dvec3 n = floor ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
      const glm::dvec3 diffuse = glm::dvec3(0.8, 0.5, 0.3) * std::exp(4.6 * random.next());
      const glm::dvec3 specular = glm::dvec3(0.04) * std::exp(4.6 * random.next());
      const double wd = luminance709(diffuse), ws = luminance709(specular);
      const glm::dvec3 axis =
          glm::normalize(n + 0.3 * glm::dvec3(random.next() - 0.5, 0.0, random.next() - 0.5));
      t[VSGL_ATTR_DIFFUSE_POWER][i] = glm::dvec4(diffuse, wd);
      t[VSGL_ATTR_DIFFUSE_POSITION][i] = glm::dvec4(wd * p, wd * glm::dot(p, p));
      t[VSGL_ATTR_DIFFUSE_AXIS][i] = glm::dvec4(wd * 0.5749 * n, (wd + ws) * (0.5 + random.next()));
      t[VSGL_ATTR_SPECULAR_POWER][i] = glm::dvec4(specular, ws);
      t[VSGL_ATTR_SPECULAR_POSITION][i] = glm::dvec4(ws * p, ws * glm::dot(p, p));
      t[VSGL_ATTR_SPECULAR_AXIS][i] = glm::dvec4(ws * 0.9 * axis, 0.0);
    }
  return t;
}

TEST(KmeansReference, CostNeverIncreasesAndNoClusterIsEmpty) {
  const AttributeTexels texels = litDisc(7);
  for (const testing_common::KmeansCase& c : kKmeansCases) {
    SCOPED_TRACE(testing_common::name(c));
    const KmeansResult r =
        kmeansReference(texels, kSize, glm::dvec3(0.0), {64, 12, c.space, c.weighting});
    ASSERT_EQ(r.costs.size(), 12u);
    for (size_t i = 1; i < r.costs.size(); ++i)
      // Lloyd's guarantee is exact; the slack is double rounding of a sum of ~700 terms.
      EXPECT_LE(r.costs[i], r.costs[i - 1] * (1.0 + 1e-12)) << "iteration " << i;
    EXPECT_LT(r.costs.back(), 0.8 * r.costs.front());  // it did cluster
    for (size_t k = 0; k < r.vsgls.size(); ++k) EXPECT_GT(r.vsgls[k].kernel.w, 0.0f) << k;
  }
}

TEST(KmeansReference, ClustersHoldAllOfTheRsmPower) {
  const AttributeTexels texels = litDisc(11);
  glm::dvec3 diffuse(0.0), specular(0.0);
  for (size_t i = 0; i < texels[0].size(); ++i) {
    diffuse += glm::dvec3(texels[VSGL_ATTR_DIFFUSE_POWER][i]);
    specular += glm::dvec3(texels[VSGL_ATTR_SPECULAR_POWER][i]);
  }
  for (const testing_common::KmeansCase& c : kKmeansCases) {
    SCOPED_TRACE(testing_common::name(c));
    const KmeansResult r =
        kmeansReference(texels, kSize, glm::dvec3(0.0), {50, 5, c.space, c.weighting});
    const auto [d, s] = testing_common::powerSums(r.vsgls);
    // Each VSGL power is the double sum rounded to fp32 once: 2^-24 relative per term.
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(d[ch], diffuse[ch], 1e-7 * diffuse[ch]);
      EXPECT_NEAR(s[ch], specular[ch], 1e-7 * specular[ch]);
    }
  }
}

TEST(KmeansReference, AnEmptyClusterTakesTheCostliestMemberOfTheWorstCluster) {
  // Five texels on a line at x = 0, 1, 2, 10, 12 (image space is ignored: features set by hand);
  // centres 0 and 1 coincide at x = 1, so cluster 1 loses every tie and is empty, and cluster 2
  // at x = 11 owns the texels at 10 and 12.
  std::vector<KmeansTexel> texels(5);
  const double xs[] = {0.0, 1.0, 2.0, 10.0, 12.0};
  for (int i = 0; i < 5; ++i) texels[i] = {glm::dvec3(xs[i], 0.0, 0.0), 1.0, true};
  const std::vector<glm::dvec3> centres = {glm::dvec3(1, 0, 0), glm::dvec3(1, 0, 0),
                                           glm::dvec3(11, 0, 0)};
  KmeansAssignment a = assignReference(texels, centres);
  EXPECT_EQ(a.counts, (std::vector<uint32_t>{3, 0, 2}));
  EXPECT_DOUBLE_EQ(a.cost, 1.0 + 0.0 + 1.0 + 1.0 + 1.0);
  ASSERT_EQ(fillEmptyClustersReference(a, texels, centres), 1u);
  // Both donors' costliest members cost 1; the tie goes to the lower cluster (0), whose
  // costliest member by the lower texel index is texel 0.
  EXPECT_EQ(a.cluster, (std::vector<uint32_t>{1, 0, 0, 2, 2}));
  EXPECT_EQ(a.counts, (std::vector<uint32_t>{2, 1, 2}));
}

TEST(KmeansReference, MoreClustersThanTexelsLeavesTheRestEmptyAndFinite) {
  std::vector<KmeansTexel> texels(3);
  for (int i = 0; i < 3; ++i) texels[i] = {glm::dvec3(i, 0.0, 0.0), 1.0, true};
  const std::vector<glm::dvec3> centres(5, glm::dvec3(0.0));
  KmeansAssignment a = assignReference(texels, centres);
  // Only cluster 0 has members; it can give up two of its three (a donor keeps one).
  EXPECT_EQ(fillEmptyClustersReference(a, texels, centres), 1u);
  EXPECT_EQ(fillEmptyClustersReference(a, texels, centres), 1u);
  EXPECT_EQ(fillEmptyClustersReference(a, texels, centres), 0u);
  EXPECT_EQ(a.counts, (std::vector<uint32_t>{1, 1, 1, 0, 0}));
}

TEST(KmeansReference, SeedsFollowThePdf) {
  // 90 % of the PDF mass in the left half of a uniform-power map: 90 % of the seeds there, to
  // within the lattice's stratification (one point per 1/N column of the warp's first split).
  AttributeTexels texels;
  for (auto& a : texels) a.assign(size_t{kSize} * kSize, glm::dvec4(0.0));
  std::vector<double> pdf(size_t{kSize} * kSize);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const size_t i = size_t{y} * kSize + x;
      texels[VSGL_ATTR_DIFFUSE_POWER][i] = glm::dvec4(1.0, 1.0, 1.0, 1.0);
      pdf[i] = x < kSize / 2 ? 9.0 : 1.0;
      texels[VSGL_ATTR_DIFFUSE_AXIS][i].w = pdf[i];
    }
  const auto clustered = kmeansTexels(texels, kSize, KMEANS_SPACE_IMAGE, KMEANS_WEIGHT_PDF);
  const auto seeds = kmeansSeeds(clustered, makeScalarPyramid(pdf, kSize), 100);
  int left = 0;
  for (const glm::dvec3& s : seeds) {
    left += s.x < 0.5;
    // Every seed is a texel centre.
    EXPECT_DOUBLE_EQ(s.x * kSize - 0.5, std::round(s.x * kSize - 0.5));
  }
  EXPECT_NEAR(left, 90, 1);
}

TEST(KmeansReference, OneClusterIsTheWholeRsmLikeTheTopLevelKernel) {
  // With N = 1 and K = 1 modified FIS reads the 1x1 level: the same sums as one cluster of
  // every texel, through the same buildVsglLobe.
  const AttributeTexels texels = litDisc(3);
  const glm::dvec3 origin(1.0, 2.0, 3.0);
  const KmeansResult r =
      kmeansReference(texels, kSize, origin, {1, 1, KMEANS_SPACE_WORLD, KMEANS_WEIGHT_PDF});
  std::array<VectorPyramid, VSGL_ATTR_COUNT> pyramids;
  std::vector<double> pdf(texels[0].size());
  for (int a = 0; a < VSGL_ATTR_COUNT; ++a) pyramids[a] = makeVectorPyramid(texels[a], kSize);
  for (size_t i = 0; i < pdf.size(); ++i) pdf[i] = texels[VSGL_ATTR_DIFFUSE_AXIS][i].w;
  const auto fis = generateVsglsReference(pyramids, makeScalarPyramid(pdf, kSize), origin, 1, 1.0,
                                          VSGL_RULE_MODIFIED);
  const auto near = [](glm::vec4 a, glm::vec4 b) {
    // Both are double results rounded to fp32; the pyramid's means reorder the sums (1e-12).
    return glm::all(glm::lessThanEqual(glm::abs(a - b), 1e-6f * (glm::abs(b) + 1e-6f)));
  };
  for (auto [a, b] : {std::pair{r.vsgls[0].diffuse, fis[0].diffuse},
                      std::pair{r.vsgls[0].specular, fis[0].specular}}) {
    EXPECT_TRUE(near(a.meanVariance, b.meanVariance));
    EXPECT_TRUE(near(a.axisSharpness, b.axisSharpness));
    EXPECT_TRUE(near(a.power, b.power));
  }
}

}  // namespace
}  // namespace gi
