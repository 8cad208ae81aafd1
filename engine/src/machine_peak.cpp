#include "engine/machine_peak.h"

#include "engine/buffer.h"
#include "engine/commands.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "shared/fma_peak.h"
#include "spirv/fma_peak.h"

namespace engine {
namespace {

// a and b keep every chain bounded (fixed point b / (1 - a) = 1) and away from denormals.
constexpr float kA = 0.9990234375f;  // 1 - 2^-10
constexpr float kB = 0.0009765625f;  // 2^-10

struct Kernel {
  explicit Kernel(Context& ctx, uint32_t threads)
      : program(ctx, "fma_peak", kFmaPeakSpv, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                sizeof(gpu::FmaPeakPush)),
        results(ctx, VkDeviceSize{threads} * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                MemoryUsage::GpuOnly) {}
  void record(VkCommandBuffer cmd, uint32_t threads, uint32_t iterations, float a, float b) {
    gpu::FmaPeakPush push{iterations, a, b, 0};
    program.dispatch(cmd, {Binding::storage(results)}, push, groupCount(threads, FMA_PEAK_GROUP));
  }
  ComputeProgram program;
  Buffer results;
};

}  // namespace

FmaPeak measureFmaPeak(Context& ctx, uint32_t threads, uint32_t iterations, uint32_t runs) {
  Kernel kernel(ctx, threads);
  GpuProfiler profiler(ctx, 2);
  std::vector<double> times;
  for (uint32_t run = 0; run <= runs; ++run) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      profiler.beginFrame(cmd);
      ProfileScope scope(&profiler, cmd, "fma peak");
      kernel.record(cmd, threads, iterations, kA, kB);
    });
    if (run > 0) times.push_back(profiler.results().at(0).ms);  // run 0 compiles the pipeline
  }
  FmaPeak peak;
  peak.ms = median(times);
  peak.flops = uint64_t{threads} * iterations * FMA_PEAK_CHAINS * 2;
  peak.gflops = double(peak.flops) / (peak.ms * 1e6);
  return peak;
}

float fmaPeakReference(uint32_t id, uint32_t iterations, float a, float b) {
  float x[FMA_PEAK_CHAINS];
  for (int c = 0; c < FMA_PEAK_CHAINS; ++c) x[c] = float(id % 1024u) * 1e-3f + float(c);
  for (uint32_t i = 0; i < iterations; ++i)
    for (float& v : x) {
      volatile float product = v * a;  // rounded on its own, as lavapipe's unfused fma
      v = product + b;
    }
  // The shader sums as dot(x0 + x1, 1): pairs first, then the four pair sums in order.
  float pairs[4];
  for (int c = 0; c < 4; ++c) pairs[c] = x[c] + x[c + 4];
  return ((pairs[0] + pairs[1]) + pairs[2]) + pairs[3];
}

std::vector<float> runFmaPeakKernel(Context& ctx, uint32_t threads, uint32_t iterations, float a,
                                    float b) {
  Kernel kernel(ctx, threads);
  ctx.submitAndWait([&](VkCommandBuffer cmd) { kernel.record(cmd, threads, iterations, a, b); });
  return kernel.results.readbackAs<float>(ctx);
}

}  // namespace engine
