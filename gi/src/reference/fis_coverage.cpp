#include "reference/fis_coverage.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace gi {

namespace {

// Texel indices i in [0, size) whose centre i + 1/2 lies in [lo, hi): i >= lo - 1/2 and
// i < hi - 1/2, i.e. [ceil(lo - 1/2), ceil(hi - 1/2)).
struct IndexRange {
  uint32_t begin = 0;
  uint32_t end = 0;
};

IndexRange coveredIndices(double lo, double hi, uint32_t size) {
  const double last = size;
  const double begin = std::clamp(std::ceil(lo - 0.5), 0.0, last);
  const double end = std::clamp(std::ceil(hi - 0.5), 0.0, last);
  return {uint32_t(begin), uint32_t(std::max(begin, end))};
}

}  // namespace

KernelCoverage measureCoverage(const ScalarPyramid& pdf, const std::vector<glm::dvec3>& kernels) {
  const uint32_t size = pdf.size;
  const std::vector<double>& base = pdf.levels.at(0);
  std::vector<uint32_t> count(base.size(), 0u);
  for (const glm::dvec3& kernel : kernels) {
    const double half = 0.5 * std::exp2(kernel.z);
    const glm::dvec2 centre = glm::dvec2(kernel) * double(size);
    const IndexRange xs = coveredIndices(centre.x - half, centre.x + half, size);
    const IndexRange ys = coveredIndices(centre.y - half, centre.y + half, size);
    for (uint32_t y = ys.begin; y < ys.end; ++y)
      for (uint32_t x = xs.begin; x < xs.end; ++x) ++count[size_t{y} * size + x];
  }
  double total = 0.0, uncovered = 0.0, multiply = 0.0;
  for (size_t i = 0; i < base.size(); ++i) {
    total += base[i];
    if (count[i] == 0) uncovered += base[i];
    if (count[i] >= 2) multiply += base[i];
  }
  if (!(total > 0.0)) return {};
  return {uncovered / total, multiply / total};
}

}  // namespace gi
