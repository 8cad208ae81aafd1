// The device's measured arithmetic and memory peaks, so that pass times can be read as a
// fraction of what the machine can do (measured on the device, not taken from a data sheet): a
// micro-kernel of independent FMA chains and a large buffer copy, timed with GPU timestamps.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
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

struct BandwidthPeak {
  double gbPerSecond = 0.0;  // median over the runs, bytes read + written per second / 1e9
  double ms = 0.0;           // median kernel time
  uint64_t bytes = 0;        // read + written per run
};

// Copies a buffer of `megabytes` MiB (far above any cache) `runs` times after one warm-up.
BandwidthPeak measureBandwidthPeak(Context& ctx, uint32_t megabytes = 64, uint32_t runs = 5);

// The kernel's copy of `source` (tests: the CPU twin is the identity).
std::vector<glm::vec4> runBandwidthPeakKernel(Context& ctx, const std::vector<glm::vec4>& source);

}  // namespace engine
