// Fixed-seed 64-bit LCG (Knuth's MMIX constants) for test inputs: portable across standard
// libraries, unlike std distributions, so every statistic a test prints is reproducible.
#pragma once

#include <cstdint>

namespace testing_common {

class Lcg {
 public:
  explicit Lcg(uint64_t seed) : state_(seed) {}
  // Uniform in [0, 1), 53 bits.
  double next() {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return double(state_ >> 11) * 0x1p-53;
  }

 private:
  uint64_t state_;
};

}  // namespace testing_common
