// Kernel coverage (gi/src/reference/fis_coverage.h): the measure itself on hand-made kernels,
// and the claim of [S3] Fig. 1 on the CPU references: on a high-frequency PDF the [T15] rule
// leaves gaps and overlaps that modified FIS ([S3] Eq. 3) reduces. Every input is a fixed
// formula, so every number below is deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "reference/fis_coverage.h"
#include "reference/vsgl_sampling.h"

namespace gi {
namespace {

// Kernel (centre, level) from a centre given in level-0 texel units of a size x size map.
glm::dvec3 kernelAt(double cx, double cy, double level, uint32_t size) {
  return {cx / size, cy / size, level};
}

TEST(FisCoverage, TwoOverlappingKernelsOnKnownTexels) {
  // 8x8 map of ones except texel (2, 1) = 5: total mass 68. Two side-2 kernels (level 1):
  // A centred at (2, 2) covers texel centres in [1, 3)^2, i.e. x, y in {1, 2};
  // B centred at (3, 2) covers x in {2, 3}, y in {1, 2}. Overlap: (2, 1) and (2, 2), mass
  // 5 + 1; union: x in {1, 2, 3}, y in {1, 2}, mass 5 + 5 * 1, so 58 is uncovered.
  const uint32_t size = 8;
  std::vector<double> base(size * size, 1.0);
  base[1 * size + 2] = 5.0;
  const ScalarPyramid pdf = makeScalarPyramid(base, size);
  const KernelCoverage c =
      measureCoverage(pdf, {kernelAt(2.0, 2.0, 1.0, size), kernelAt(3.0, 2.0, 1.0, size)});
  EXPECT_DOUBLE_EQ(c.multiplyCoveredMass, 6.0 / 68.0);
  EXPECT_DOUBLE_EQ(c.uncoveredMass, 58.0 / 68.0);

  // A third kernel at the map's corner (0, 0), side 2, spans [-1, 1)^2: only texel (0, 0) is
  // inside the map. It overlaps nothing, so only the gaps shrink, by that texel's mass.
  const KernelCoverage corner =
      measureCoverage(pdf, {kernelAt(2.0, 2.0, 1.0, size), kernelAt(3.0, 2.0, 1.0, size),
                            kernelAt(0.0, 0.0, 1.0, size)});
  EXPECT_DOUBLE_EQ(corner.multiplyCoveredMass, 6.0 / 68.0);
  EXPECT_DOUBLE_EQ(corner.uncoveredMass, 57.0 / 68.0);
}

TEST(FisCoverage, IntegerSideSquaresCoverExactlySideSquaredTexels) {
  // Half-open squares: a side-s kernel (s = 1, 2, 4) anywhere inside the map covers s^2 texels,
  // also when its edges pass exactly through texel centres (offsets 0 and 1/2).
  const uint32_t size = 16;
  const ScalarPyramid uniform = makeScalarPyramid(std::vector<double>(size * size, 1.0), size);
  const double texels = double(size) * size;
  for (double level : {0.0, 1.0, 2.0}) {
    const double side = std::exp2(level);
    for (double offset : {0.0, 0.25, 0.5, 0.75}) {
      const KernelCoverage c =
          measureCoverage(uniform, {kernelAt(8.0 + offset, 7.0 + offset, level, size)});
      EXPECT_DOUBLE_EQ(c.uncoveredMass, 1.0 - side * side / texels)
          << "level " << level << " offset " << offset;
      EXPECT_EQ(c.multiplyCoveredMass, 0.0);
    }
  }
  // A level-L kernel (side 16) covers the whole map only from its centre: from (3, 12) it spans
  // [-5, 11) x [4, 20), i.e. 11 x 12 texels inside the map. No kernels leave it all uncovered.
  EXPECT_EQ(measureCoverage(uniform, {kernelAt(8.0, 8.0, 4.0, size)}).uncoveredMass, 0.0);
  EXPECT_DOUBLE_EQ(measureCoverage(uniform, {kernelAt(3.0, 12.0, 4.0, size)}).uncoveredMass,
                   1.0 - 11.0 * 12.0 / texels);
  EXPECT_EQ(measureCoverage(uniform, {}).uncoveredMass, 1.0);
  // An all-zero PDF has no mass: both fractions 0.
  const ScalarPyramid zero = makeScalarPyramid(std::vector<double>(size * size, 0.0), size);
  const KernelCoverage none = measureCoverage(zero, {kernelAt(8.0, 8.0, 1.0, size)});
  EXPECT_EQ(none.uncoveredMass, 0.0);
  EXPECT_EQ(none.multiplyCoveredMass, 0.0);
}

// 64x64: a checkerboard of single texels (period 2) with values 1 and 0.02, modulated by a
// smooth diagonal ramp from 0.25 to 1, the high-frequency PDF of [S3] Fig. 1.
std::vector<double> checkerGradientPdf(uint32_t size) {
  std::vector<double> base(size_t{size} * size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const double ramp = 0.25 + 0.75 * double(x + y) / double(2 * (size - 1));
      base[size_t{y} * size + x] = ((x + y) % 2 == 0 ? 1.0 : 0.02) * ramp;
    }
  return base;
}

std::vector<glm::dvec3> latticeKernels(const ScalarPyramid& pdf, uint32_t n, uint32_t rule) {
  std::vector<glm::dvec3> kernels;
  for (uint32_t i = 0; i < n; ++i) {
    const WarpResult warp = warpHierarchical(pdf, fibonacciPoint(i, n));
    const double level = rule == VSGL_RULE_MODIFIED ? modifiedFisLevel(pdf, warp.x, n, 1.0)
                                                    : tok15Level(warp.density, n, 1.0, pdf.size);
    kernels.emplace_back(warp.x, level);
  }
  return kernels;
}

TEST(FisCoverage, ModifiedFisTilesAHighFrequencyPdfBetterThanTok15) {
  const uint32_t size = 64, n = 256;
  const ScalarPyramid pdf = makeScalarPyramid(checkerGradientPdf(size), size);
  const KernelCoverage tok15 = measureCoverage(pdf, latticeKernels(pdf, n, VSGL_RULE_TOK15));
  const KernelCoverage modified = measureCoverage(pdf, latticeKernels(pdf, n, VSGL_RULE_MODIFIED));
  const double tok15Bad = tok15.uncoveredMass + tok15.multiplyCoveredMass;
  const double modifiedBad = modified.uncoveredMass + modified.multiplyCoveredMass;
  std::printf("64^2 checker x ramp, N = %u, K = 1 (fractions of PDF mass):\n", n);
  std::printf("  Tok15:    uncovered %.4f  multiply covered %.4f  sum %.4f\n", tok15.uncoveredMass,
              tok15.multiplyCoveredMass, tok15Bad);
  std::printf("  modified: uncovered %.4f  multiply covered %.4f  sum %.4f\n",
              modified.uncoveredMass, modified.multiplyCoveredMass, modifiedBad);
  // Measured: Tok15 0.377 + 0.108 = 0.485, modified 0.160 + 0.143 = 0.304. Modified FIS wins by
  // closing gaps: its kernels on the bright texels are sized by the filtered mass (about 4x4
  // texels) where [T15] uses the centre's density, twice the local mean, and shrinks them to
  // half that area; its overlaps are slightly larger here. The asserted margin, 0.1 of the
  // mass, is about half the measured gap of 0.18: the computation is deterministic, and a
  // kernel changing its level by a rounding flip moves about 1 / N = 0.004 of mass, so only a
  // real change of either rule can close it.
  EXPECT_LT(modifiedBad + 0.1, tok15Bad);
}

}  // namespace
}  // namespace gi
