// Exact-mean mip pyramids: the GPU's fp32 2x2 reductions against exact double means.
// Error bound: each level sums 4 values as (a + b) + (c + d) and scales by an exact 1/4, so for
// non-negative data a level adds at most 2 roundings, i.e. relative error <= 2 L u after L
// levels (u = 2^-24): 7.2e-7 for a 64^2 pyramid (L = 6), inside the 1e-6 the VSGL sums require.
// For signed data (position sums) the same bound holds relative to the mean of |values|.
#include <cmath>
#include <cstring>
#include <random>

#include "engine/commands.h"
#include "gpu_fixture.h"
#include "passes/mip_pyramid.h"
#include "reference/mip_reference.h"

namespace {

class MipPyramidTest : public testing_gpu::GpuTest {
 protected:
  // Uploads `base` into level 0 of a pyramid, reduces it on the GPU and reads every level back.
  std::vector<std::vector<glm::vec4>> reduce(const std::vector<glm::vec4>& base, uint32_t size) {
    engine::Image pyramid = gi::createPyramid(ctx(), size);
    std::vector<glm::vec4> texels(base);
    for (uint32_t level = 1; level < pyramid.desc().mips; ++level)
      texels.resize(texels.size() + (size_t{size} >> level) * (size >> level));
    pyramid.upload(ctx(), texels.data(), texels.size() * sizeof(glm::vec4));
    gi::MipPyramid mips(ctx());
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      engine::imageBarrier(cmd, pyramid, VK_IMAGE_LAYOUT_GENERAL);
      mips.record(cmd, pyramid);
    });
    std::vector<std::vector<glm::vec4>> levels;
    for (uint32_t level = 0; level < pyramid.desc().mips; ++level) {
      levels.push_back(pyramid.readbackRgba32f(ctx(), level));
    }
    return levels;
  }

  // Compares every level against exact means; `scale(level, texel)` is the magnitude the error
  // is relative to.
  void compare(const std::vector<glm::vec4>& base, uint32_t size, bool signedData) {
    auto gpu = reduce(base, size);
    std::vector<glm::dvec4> exact(base.begin(), base.end()), absolute(base.size());
    for (size_t i = 0; i < base.size(); ++i) absolute[i] = glm::abs(glm::dvec4(base[i]));
    auto ref = gi::mipReference(exact, size);
    auto mag = gi::mipReference(absolute, size);
    ASSERT_EQ(gpu.size(), ref.size());
    const double u = std::ldexp(1.0, -24);
    double worst = 0.0;
    for (size_t level = 1; level < ref.size(); ++level) {
      const double bound = 2.0 * static_cast<double>(level) * u;
      for (size_t i = 0; i < ref[level].size(); ++i)
        for (int k = 0; k < 4; ++k) {
          double m = signedData ? mag[level][i][k] : std::abs(ref[level][i][k]);
          double err = std::abs(gpu[level][i][k] - ref[level][i][k]);
          worst = std::max(worst, m > 0.0 ? err / m : err);
          ASSERT_LE(err, bound * m) << "level " << level << " texel " << i << " channel " << k;
        }
    }
    std::printf("worst relative error %.2e (bound %.2e)\n", worst,
                2.0 * double(ref.size() - 1) * u);
  }
};

TEST_F(MipPyramidTest, PositiveDataOverSixDecadesMatchesExactMeans) {
  const uint32_t size = 64;
  std::mt19937 rng(5);
  std::vector<glm::vec4> base(size_t{size} * size);
  for (auto& v : base)
    for (int k = 0; k < 4; ++k)
      v[k] = std::ldexp(static_cast<float>(rng() >> 8) * 0x1p-24f + 0.5f, int(rng() % 20) - 10);
  base[100] = glm::vec4(0.0f);  // zero power texels are common (background)
  compare(base, size, false);
}

TEST_F(MipPyramidTest, SignedDataMatchesExactMeansRelativeToMagnitude) {
  const uint32_t size = 32;
  std::mt19937 rng(9);
  std::vector<glm::vec4> base(size_t{size} * size);
  for (auto& v : base)
    for (int k = 0; k < 4; ++k) v[k] = (static_cast<float>(rng() >> 8) * 0x1p-24f - 0.5f) * 100.0f;
  compare(base, size, true);
}

TEST_F(MipPyramidTest, TopLevelOfAConstantImageIsThatConstant) {
  const uint32_t size = 16;
  std::vector<glm::vec4> base(size_t{size} * size, glm::vec4(0.1f, 3.0f, -2.5f, 1e-20f));
  auto gpu = reduce(base, size);
  // Power-of-two scaling of identical values is exact at every level.
  EXPECT_EQ(gpu.back().at(0), base[0]);
}

TEST_F(MipPyramidTest, RefusesSizesThatAreNotPowersOfTwo) {
  // Non-power-of-two maps break the exact-mean property; callers pad them instead.
  EXPECT_THROW(gi::createPyramid(ctx(), 48), engine::Error);
}

}  // namespace
