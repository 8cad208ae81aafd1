// The FMA-throughput micro-kernel (shaders/bench/fma_peak.comp): every thread runs
// FMA_PEAK_CHAINS independent chains x <- x * a + b for `iterations` steps and writes their sum,
// so no step can be optimised away. Reported as 2 flops per step: multiply and add.
#ifndef SHADERS_SHARED_FMA_PEAK_H
#define SHADERS_SHARED_FMA_PEAK_H
#include "interop.h"

#define FMA_PEAK_GROUP 64
// Independent chains per thread: enough to hide the latency of a dependent FMA (lavapipe
// measured: one dependent chain reaches about half the peak, four or more the peak).
#define FMA_PEAK_CHAINS 8  // two vec4 registers

SHARED_BEGIN

struct FmaPeakPush {
  uint iterations;
  float a;  // multiplier, |a| < 1 keeps the chains bounded
  float b;  // addend
  uint pad;
};

SHARED_END

SHARED_ASSERT_SIZE(FmaPeakPush, 16);
#endif
