// Sharing the VSGLs among RSM views (gi/src/passes/vsgl_allocation.h): vsgl_allocate.comp against
// its fp32 twin, exactly, on weights of every kind; the shares follow the weights; and no power
// at all gives equal shares.
#include <random>

#include "gpu_fixture.h"
#include "passes/vsgl_allocation.h"
#include "reference/vsgl_allocation_reference.h"

namespace {

class VsglAllocationTest : public testing_gpu::GpuTest {
 protected:
  std::vector<glm::uvec2> allocate(const std::vector<glm::vec2>& weights, float fluxMix,
                                   uint32_t count) {
    gi::VsglAllocation allocation(ctx());
    std::vector<gpu::VsglViewWeight> records(weights.size());
    for (size_t v = 0; v < weights.size(); ++v)
      records[v].weight = glm::vec4(weights[v], 0.0f, 0.0f);
    allocation.weights().upload(ctx(), std::span<const gpu::VsglViewWeight>(records));
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      allocation.recordAllocate(cmd, uint32_t(weights.size()), count, fluxMix);
    });
    std::vector<glm::uvec2> ranges;
    const auto out = allocation.ranges().readbackAs<gpu::VsglViewRange>(ctx());
    for (size_t v = 0; v < weights.size(); ++v) ranges.emplace_back(out[v].range.x, out[v].range.y);
    return ranges;
  }
};

// Random weights (some views without power, some without importance), 1 to 48 views, N from 1
// to 4096, both PDFs: the GPU's ranges equal the twin's, contiguous and adding up to N.
TEST_F(VsglAllocationTest, MatchesItsTwin) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int trial = 0; trial < 40; ++trial) {
    const auto views = static_cast<uint32_t>(1 + rng() % VSGL_MAX_VIEWS);
    const uint32_t count = std::vector<uint32_t>{1, 7, 62, 512, 4096}[trial % 5];
    const float fluxMix = trial % 2 ? 1.0f : 0.1f;
    std::vector<glm::vec2> weights(views);
    for (glm::vec2& w : weights) {
      w = {unit(rng) < 0.2f ? 0.0f : std::exp(8.0f * unit(rng) - 4.0f),
           unit(rng) < 0.2f ? 0.0f : std::exp(8.0f * unit(rng) - 4.0f)};
    }
    SCOPED_TRACE("trial " + std::to_string(trial));
    const std::vector<glm::uvec2> gpu = allocate(weights, fluxMix, count);
    const std::vector<glm::uvec2> cpu = gi::allocateVsglsReference(weights, fluxMix, count);
    uint32_t first = 0;
    for (uint32_t v = 0; v < views; ++v) {
      ASSERT_EQ(gpu[v], cpu[v]) << "view " << v;
      EXPECT_EQ(gpu[v].x, first);
      first += gpu[v].y;
    }
    EXPECT_EQ(first, count);
  }
}

// Shares follow the weights: 9 : 1 of the flux gives 90 and 10 of 100 VSGLs with the flux PDF;
// with the BRSM PDF (mix 0.1) a view with 9x the importance and the same power gets
// (0.9 * 0.9 + 0.1 * 0.5) of them: 86 of 100.
TEST_F(VsglAllocationTest, SharesFollowTheWeights) {
  EXPECT_EQ(allocate({{9.0f, 9.0f}, {1.0f, 1.0f}}, 1.0f, 100),
            (std::vector<glm::uvec2>{{0, 90}, {90, 10}}));
  EXPECT_EQ(allocate({{1.0f, 9.0f}, {1.0f, 1.0f}}, 0.1f, 100),
            (std::vector<glm::uvec2>{{0, 86}, {86, 14}}));
  // A view without power gets nothing.
  EXPECT_EQ(allocate({{0.0f, 0.0f}, {2.0f, 5.0f}, {0.0f, 0.0f}}, 0.1f, 64),
            (std::vector<glm::uvec2>{{0, 0}, {0, 64}, {64, 0}}));
}

// Nothing bounced (a light whose every face sees the sky): equal shares, remainder to the first.
TEST_F(VsglAllocationTest, NoPowerGivesEqualShares) {
  EXPECT_EQ(allocate(std::vector<glm::vec2>(6, glm::vec2(0.0f)), 0.1f, 62),
            (std::vector<glm::uvec2>{{0, 11}, {11, 11}, {22, 10}, {32, 10}, {42, 10}, {52, 10}}));
}

}  // namespace
