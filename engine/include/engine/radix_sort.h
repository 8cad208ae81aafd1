// A stable, deterministic GPU sort of (uint32 key, uint32 value) pairs by the low keyBits bits
// of the key: LSD radix sort with 4-bit digits, ceil(keyBits / 4) passes of three dispatches
// (histogram, one-group scan, scatter; shaders/shared/radix_sort.h). Equal keys keep their input
// order, and the output is bit-identical on every run: offsets and ranks are integer sums in a
// fixed order (the only atomics count digits, where the order of additions cannot matter).
#pragma once

#include <cstdint>

#include "engine/buffer.h"
#include "engine/profiler.h"
#include "engine/program.h"

namespace engine {

class RadixSort {
 public:
  // Owns the scratch for up to maxCount pairs: a second key and value buffer (the passes
  // ping-pong between them and the caller's) and the digit table (16 counts per 2048 pairs).
  RadixSort(Context& ctx, uint32_t maxCount);

  // Sorts keys[0, count) and values[0, count) in place, by key & (2^keyBits - 1); the caller
  // guarantees the key bits above keyBits are zero. Both are uint32 storage buffers; when
  // ceil(keyBits / 4) is odd the result is copied back into them, so a borrowed buffer needs
  // VK_BUFFER_USAGE_TRANSFER_DST_BIT. The caller orders earlier writes of the pairs with a
  // barrier; record ends with one that makes the sorted pairs visible to later compute passes.
  // Throws engine::Error, before recording anything, if count > maxCount or keyBits is outside
  // [1, 32].
  void record(VkCommandBuffer cmd, const Buffer& keys, const Buffer& values, uint32_t count,
              uint32_t keyBits, GpuProfiler* profiler = nullptr,
              const char* passName = "radix sort") const;

  uint32_t maxCount() const { return maxCount_; }

 private:
  uint32_t maxCount_;
  ComputeProgram histogram_;
  ComputeProgram scan_;
  ComputeProgram scatter_;
  Buffer scratchKeys_;
  Buffer scratchValues_;
  Buffer table_;
};

}  // namespace engine
