// The device's measured arithmetic peak, so that pass times can be read as a fraction of what
// the machine can do (design.md "measured, not guessed"): a micro-kernel of independent FMA
// chains timed with GPU timestamps.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/vk_context.h"

namespace engine {

struct FmaPeak {
  double gflops = 0.0;  // median over the runs, 2 flops per FMA
  double ms = 0.0;      // median kernel time
  uint64_t flops = 0;   // per run
};

// Runs the kernel `runs` times (after one warm-up) with `threads` threads of `iterations` steps.
FmaPeak measureFmaPeak(Context& ctx, uint32_t threads = 1u << 16, uint32_t iterations = 4096,
                       uint32_t runs = 5);

// What thread `id` of fma_peak.comp writes, in float with the multiply and add rounded apart
// (lavapipe's fma is a multiply and an add; a fused device differs by a few ulps per step).
float fmaPeakReference(uint32_t id, uint32_t iterations, float a, float b);

// The kernel's results for `threads` threads (tests).
std::vector<float> runFmaPeakKernel(Context& ctx, uint32_t threads, uint32_t iterations, float a,
                                    float b);

}  // namespace engine
