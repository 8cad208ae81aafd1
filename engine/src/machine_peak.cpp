#include "engine/machine_peak.h"

#include <functional>

#include "engine/buffer.h"
#include "engine/commands.h"
#include "engine/profiler.h"
#include "engine/program.h"
#include "shared/bandwidth_peak.h"
#include "shared/fma_peak.h"
#include "spirv/bandwidth_peak.h"
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

struct CopyKernel {
  CopyKernel(Context& ctx, VkDeviceSize bytes)
      : program(ctx, "bandwidth_peak", kBandwidthPeakSpv,
                {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                sizeof(gpu::BandwidthPeakPush)),
        source(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly),
        destination(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly) {}
  void record(VkCommandBuffer cmd) {
    const auto count = static_cast<uint32_t>(source.size() / sizeof(glm::vec4));
    gpu::BandwidthPeakPush push{count, 0, 0, 0};
    program.dispatch(cmd, {Binding::storage(source), Binding::storage(destination)}, push,
                     groupCount(count, BANDWIDTH_PEAK_GROUP * BANDWIDTH_PEAK_PER_THREAD));
  }
  ComputeProgram program;
  Buffer source;
  Buffer destination;
};

// Median GPU time of `record` over `runs` submissions, after one that compiles the pipeline.
double medianKernelMs(Context& ctx, uint32_t runs,
                      const std::function<void(VkCommandBuffer)>& record) {
  GpuProfiler profiler(ctx, 2);
  std::vector<double> times;
  for (uint32_t run = 0; run <= runs; ++run) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      profiler.beginFrame(cmd);
      ProfileScope scope(&profiler, cmd, "peak kernel");
      record(cmd);
    });
    if (run > 0) times.push_back(profiler.results().at(0).ms);
  }
  return median(times);
}

}  // namespace

FmaPeak measureFmaPeak(Context& ctx, uint32_t threads, uint32_t iterations, uint32_t runs) {
  Kernel kernel(ctx, threads);
  FmaPeak peak;
  peak.ms = medianKernelMs(
      ctx, runs, [&](VkCommandBuffer cmd) { kernel.record(cmd, threads, iterations, kA, kB); });
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

BandwidthPeak measureBandwidthPeak(Context& ctx, uint32_t megabytes, uint32_t runs) {
  CopyKernel kernel(ctx, VkDeviceSize{megabytes} << 20);
  // Written once so the copy reads real data (a never-written allocation may be lazily backed).
  ctx.submitAndWait([&](VkCommandBuffer cmd) { fillBuffer(cmd, kernel.source, 0x3f800000u); });
  BandwidthPeak peak;
  peak.ms = medianKernelMs(ctx, runs, [&](VkCommandBuffer cmd) { kernel.record(cmd); });
  peak.bytes = 2 * kernel.source.size();
  peak.gbPerSecond = double(peak.bytes) / (peak.ms * 1e6);
  return peak;
}

std::vector<glm::vec4> runBandwidthPeakKernel(Context& ctx, const std::vector<glm::vec4>& source) {
  CopyKernel kernel(ctx, source.size() * sizeof(glm::vec4));
  kernel.source.upload(ctx, source.data(), source.size() * sizeof(glm::vec4));
  ctx.submitAndWait([&](VkCommandBuffer cmd) { kernel.record(cmd); });
  return kernel.destination.readbackAs<glm::vec4>(ctx);
}

}  // namespace engine
