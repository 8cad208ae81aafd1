// Relative RMS, sqrt(sum |a - b|^2 / sum |b|^2) over pixels and channels: the error measure of
// the environment-lighting tests against their references.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

namespace testing_common {

struct RelativeRms {
  double error2 = 0.0, value2 = 0.0;
  void add(glm::dvec3 got, glm::dvec3 want) {
    const glm::dvec3 d = got - want;
    error2 += glm::dot(d, d);
    value2 += glm::dot(want, want);
  }
  double relative() const { return std::sqrt(error2 / value2); }
};

}  // namespace testing_common
