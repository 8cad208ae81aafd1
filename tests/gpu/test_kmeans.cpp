// The k-means baseline on the GPU (gi/src/passes/kmeans.h) against its CPU twin
// (gi/src/reference/kmeans_reference.h) on real RSMs: assignment and sums for the same centres,
// the cost over iterations, no empty clusters, conservation of the RSM's power, and
// determinism.
#include <cmath>

#include "gpu_fixture.h"
#include "kmeans_cases.h"
#include "passes/kmeans.h"
#include "reference/kmeans_reference.h"
#include "rsm_rig.h"

namespace {

using testing_common::kKmeansCases;

class KmeansTest : public testing_gpu::GpuTest {
 protected:
  static constexpr uint32_t kSize = 64;
  static constexpr uint32_t kClusters = 96;

  // The cornell box's RSM (or `scene`'s) and its attribute pyramids, with the CPU's copy of
  // level 0.
  void build(const std::string& scene = "cornell") {
    rig_ = std::make_unique<testing_gpu::RsmRig>(ctx(), scene, kSize);
    rig_->buildAttributes(ctx());
    kmeans_ = std::make_unique<gi::KmeansClustering>(ctx(), kSize, kClusters);
    for (int a = 0; a < VSGL_ATTR_COUNT; ++a) {
      texels_[a].clear();
      for (const glm::vec4& v : rig_->attributes->pyramid(a).readbackRgba32f(ctx(), 0))
        texels_[a].emplace_back(v);
    }
    pdf_.clear();
    for (const glm::dvec4& v : texels_[VSGL_ATTR_DIFFUSE_AXIS]) pdf_.push_back(v.w);
  }

  void run(const gi::KmeansPassSettings& settings) {
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      kmeans_->record(cmd, *rig_->attributes, rig_->view, settings);
    });
  }

  std::vector<glm::dvec3> gpuCentres(uint32_t clusters) {
    std::vector<glm::dvec3> out;
    auto c = kmeans_->centres().readbackAs<glm::vec4>(ctx());
    for (uint32_t k = 0; k < clusters; ++k) out.emplace_back(c[k]);
    return out;
  }

  void uploadCentres(const std::vector<glm::dvec3>& centres, uint32_t space) {
    std::vector<glm::vec4> c;
    for (const glm::dvec3& x : centres) c.emplace_back(glm::vec3(x), 0.0f);
    kmeans_->centres().upload(ctx(), c.data(), c.size() * sizeof(glm::vec4));
    kmeans_->adoptCentres(static_cast<uint32_t>(centres.size()), space);
  }

  // The last iteration's cluster of every texel, from the sorted pairs (K = none).
  std::vector<uint32_t> gpuAssignment() {
    auto keys = kmeans_->sortedClusters().readbackAs<uint32_t>(ctx());
    auto values = kmeans_->sortedTexels().readbackAs<uint32_t>(ctx());
    std::vector<uint32_t> cluster(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) cluster.at(values[i]) = keys[i];
    return cluster;
  }

  std::vector<gpu::Vsgl> gpuVsgls(uint32_t clusters) {
    auto v = kmeans_->vsgls().readbackAs<gpu::Vsgl>(ctx());
    v.resize(clusters);
    return v;
  }

  std::unique_ptr<testing_gpu::RsmRig> rig_;
  std::unique_ptr<gi::KmeansClustering> kmeans_;
  gi::AttributeTexels texels_;
  std::vector<double> pdf_;
};

TEST_F(KmeansTest, AssignmentAndSumsMatchTheReferenceForTheSameCentres) {
  build();
  for (const testing_common::KmeansCase& c : kKmeansCases) {
    SCOPED_TRACE(testing_common::name(c));
    const auto clustered = gi::kmeansTexels(texels_, kSize, c.space, c.weighting);
    const auto centres = gi::kmeansSeeds(clustered, gi::makeScalarPyramid(pdf_, kSize), kClusters);
    uploadCentres(centres, c.space);
    run({kClusters, 1, c.space, c.weighting, true});
    const std::vector<uint32_t> gpu = gpuAssignment();
    gi::KmeansAssignment cpu = gi::assignReference(clustered, centres);
    const uint32_t filled = gi::fillEmptyClustersReference(cpu, clustered, centres);
    EXPECT_EQ(kmeans_->filledPerIteration().readbackAs<uint32_t>(ctx()).at(0), filled);
    // The GPU's fp32 distances may pick the other centre of a near tie: a pick is accepted when
    // its distance is within 4 ulps of |f|^2 + |c|^2 (the magnitude the fp32 difference rounds
    // at) of the exact nearest.
    size_t differ = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
      if (gpu[i] == cpu.cluster[i]) continue;
      ++differ;
      ASSERT_TRUE(clustered[i].powered && gpu[i] < kClusters) << "texel " << i;
      const glm::dvec3 f = clustered[i].feature;
      const glm::dvec3 a = centres[gpu[i]], b = centres[cpu.cluster[i]];
      const double scale = glm::dot(f, f) + std::max(glm::dot(a, a), glm::dot(b, b));
      EXPECT_NEAR(glm::dot(f - a, f - a), glm::dot(f - b, f - b), 4.0 * 0x1p-24 * scale)
          << "texel " << i;
    }
    EXPECT_LE(differ, 4u);
    // Sums over the GPU's own assignment.
    gi::KmeansAssignment same = cpu;
    same.cluster = gpu;
    std::fill(same.counts.begin(), same.counts.end(), 0u);
    for (uint32_t k : gpu)
      if (k < kClusters) ++same.counts[k];
    const gi::KmeansClusters ref =
        gi::sumClustersReference(texels_, clustered, same, centres, glm::dvec3(rig_->view.origin));
    const auto vsgls = gpuVsgls(kClusters);
    const auto newCentres = gpuCentres(kClusters);
    // fp32 sums of up to ~1000 texels (64 strided runs and a 6-level tree): 1e-5 relative for
    // powers, means and centres; sharpness goes through Banerjee's 1 / (1 - r), so 1e-3, and
    // the variance is a difference of two such sums, so 1e-3 of the mean's squared size.
    for (uint32_t k = 0; k < kClusters; ++k) {
      SCOPED_TRACE("cluster " + std::to_string(k));
      EXPECT_EQ(vsgls[k].kernel.w, float(same.counts[k]));
      for (auto [g, r] : {std::pair{vsgls[k].diffuse, ref.vsgls[k].diffuse},
                          std::pair{vsgls[k].specular, ref.vsgls[k].specular}}) {
        for (int ch = 0; ch < 4; ++ch)
          EXPECT_NEAR(g.power[ch], r.power[ch], 1e-5 * std::abs(r.power[ch]) + 1e-30);
        const double extent = glm::length(glm::dvec3(r.meanVariance));
        for (int ch = 0; ch < 3; ++ch)
          EXPECT_NEAR(g.meanVariance[ch], r.meanVariance[ch], 1e-5 * extent);
        EXPECT_NEAR(g.meanVariance.w, r.meanVariance.w, 1e-3 * (r.meanVariance.w + 1e-4));
        EXPECT_GT(glm::dot(glm::dvec3(g.axisSharpness), glm::dvec3(r.axisSharpness)), 1.0 - 1e-6);
        EXPECT_NEAR(g.axisSharpness.w, r.axisSharpness.w, 1e-3 * r.axisSharpness.w);
      }
      const double extent = glm::length(ref.centres[k]) + 1e-3;
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(newCentres[k][ch], ref.centres[k][ch], 1e-5 * extent);
    }
  }
}

// The weighted cost of the nearest assignment, in double, for centres read back from the GPU.
double cost(const std::vector<gi::KmeansTexel>& texels, const std::vector<glm::dvec3>& centres) {
  return gi::assignReference(texels, centres).cost;
}

TEST_F(KmeansTest, CostNeverIncreasesAcrossIterations) {
  build();
  for (const testing_common::KmeansCase& c : kKmeansCases) {
    SCOPED_TRACE(testing_common::name(c));
    const auto clustered = gi::kmeansTexels(texels_, kSize, c.space, c.weighting);
    run({kClusters, 1, c.space, c.weighting, false});
    std::vector<double> costs;
    // One iteration per record, each starting from the last one's centres.
    for (int it = 0; it < 8; ++it) {
      costs.push_back(cost(clustered, gpuCentres(kClusters)));
      run({kClusters, 1, c.space, c.weighting, true});
    }
    // Lloyd's guarantee is exact for exact means; the GPU's fp32 means and near-tie picks move
    // the cost by rounding only: 1e-6 relative.
    for (size_t i = 1; i < costs.size(); ++i)
      EXPECT_LE(costs[i], costs[i - 1] * (1.0 + 1e-6)) << "iteration " << i;
    EXPECT_LT(costs.back(), costs.front());
  }
}

TEST_F(KmeansTest, EveryClusterHasMembersAndTheClustersHoldAllThePower) {
  for (const std::string& scene : engine::builtinSceneNames()) {
    build(scene);
    glm::dvec3 diffuse(0.0), specular(0.0);
    for (size_t i = 0; i < texels_[0].size(); ++i) {
      diffuse += glm::dvec3(texels_[VSGL_ATTR_DIFFUSE_POWER][i]);
      specular += glm::dvec3(texels_[VSGL_ATTR_SPECULAR_POWER][i]);
    }
    for (const testing_common::KmeansCase& c : kKmeansCases) {
      SCOPED_TRACE(scene + ", " + testing_common::name(c));
      run({kClusters, 4, c.space, c.weighting, false});
      const std::vector<gpu::Vsgl> vsgls = gpuVsgls(kClusters);
      for (const gpu::Vsgl& v : vsgls) EXPECT_GE(v.kernel.w, 1.0f);
      const auto [d, s] = testing_common::powerSums(vsgls);
      // fp32 sums of ~4000 texels: well inside the 1e-5.
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(d[ch], diffuse[ch], 1e-5 * diffuse[ch]);
        EXPECT_NEAR(s[ch], specular[ch], 1e-5 * specular[ch]);
      }
    }
  }
}

TEST_F(KmeansTest, DuplicatedCentresAreFilledAndTheRunIsDeterministic) {
  build();
  const auto clustered = gi::kmeansTexels(texels_, kSize, KMEANS_SPACE_WORLD, KMEANS_WEIGHT_PDF);
  auto centres = gi::kmeansSeeds(clustered, gi::makeScalarPyramid(pdf_, kSize), kClusters);
  for (uint32_t k = 1; k < 6; ++k) centres[k] = centres[0];  // five clusters lose every tie
  uploadCentres(centres, KMEANS_SPACE_WORLD);
  run({kClusters, 3, KMEANS_SPACE_WORLD, KMEANS_WEIGHT_PDF, true});
  EXPECT_EQ(kmeans_->filledPerIteration().readbackAs<uint32_t>(ctx()).at(0), 5u);
  const auto first = gpuVsgls(kClusters);
  for (const gpu::Vsgl& v : first) EXPECT_GE(v.kernel.w, 1.0f);
  uploadCentres(centres, KMEANS_SPACE_WORLD);
  run({kClusters, 3, KMEANS_SPACE_WORLD, KMEANS_WEIGHT_PDF, true});
  const auto second = gpuVsgls(kClusters);
  EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(gpu::Vsgl)), 0);
}

}  // namespace
