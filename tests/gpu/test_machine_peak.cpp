// The machine-peak micro-kernels compute what their CPU twins compute (so the flops and bytes
// they are credited with were really done), and the measurements report finite, positive rates.
#include <cmath>

#include "engine/machine_peak.h"
#include "gpu_fixture.h"

namespace {

using MachinePeakTest = testing_gpu::GpuTest;

// Each chain contracts toward 1 by a = 1 - 2^-10 per step, so a rounding difference made at any
// step decays: a fused device (one rounding per step instead of two, <= 1 ulp ~ 1e-6 at values
// below 8) can drift by at most 2^10 ulps per chain, 8 chains: 1e-2 absolute on a sum of ~36.
// Lavapipe rounds the multiply and the add apart, like the reference, and matches exactly.
TEST_F(MachinePeakTest, KernelMatchesReference) {
  constexpr uint32_t kThreads = 256, kIterations = 1000;
  constexpr float kA = 0.9990234375f, kB = 0.0009765625f;
  const std::vector<float> gpu = engine::runFmaPeakKernel(ctx(), kThreads, kIterations, kA, kB);
  ASSERT_EQ(gpu.size(), kThreads);
  double worst = 0.0;
  for (uint32_t id = 0; id < kThreads; ++id) {
    const float want = engine::fmaPeakReference(id, kIterations, kA, kB);
    worst = std::max(worst, double(std::abs(gpu[id] - want)));
    EXPECT_NEAR(gpu[id], want, 1e-2) << "thread " << id;
  }
  std::printf("largest |gpu - cpu| = %.3g\n", worst);
}

TEST_F(MachinePeakTest, MeasuresAPositiveRate) {
  const engine::FmaPeak peak = engine::measureFmaPeak(ctx(), 1u << 12, 256, 2);
  EXPECT_TRUE(std::isfinite(peak.gflops));
  EXPECT_GT(peak.gflops, 0.0);
  EXPECT_EQ(peak.flops, uint64_t{1u << 12} * 256 * 8 * 2);
}

TEST_F(MachinePeakTest, CopyKernelCopiesEveryElement) {
  // 1000 vec4s: not a multiple of the group size, so the bounds check is exercised too.
  std::vector<glm::vec4> source(1000);
  for (size_t i = 0; i < source.size(); ++i)
    source[i] = glm::vec4(float(i), -float(i), 0.5f, 1e30f);
  EXPECT_EQ(engine::runBandwidthPeakKernel(ctx(), source), source);
}

TEST_F(MachinePeakTest, MeasuresAPositiveBandwidth) {
  const engine::BandwidthPeak peak = engine::measureBandwidthPeak(ctx(), 4, 2);
  EXPECT_TRUE(std::isfinite(peak.gbPerSecond));
  EXPECT_GT(peak.gbPerSecond, 0.0);
  EXPECT_EQ(peak.bytes, uint64_t{2} << 22);
}

}  // namespace
