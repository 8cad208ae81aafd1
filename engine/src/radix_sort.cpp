#include "engine/radix_sort.h"

#include <algorithm>
#include <cassert>
#include <string>
#include <vector>

#include "engine/commands.h"
#include "shared/radix_sort.h"
#include "spirv/radix_histogram.h"
#include "spirv/radix_scan.h"
#include "spirv/radix_scatter.h"

namespace engine {
namespace {

Buffer storageBuffer(Context& ctx, VkDeviceSize bytes) {
  // Vulkan forbids empty buffers; maxCount 0 still gets a valid (unused) one.
  return Buffer(ctx, std::max<VkDeviceSize>(bytes, 4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                MemoryUsage::GpuOnly);
}

std::vector<VkDescriptorType> storageBindings(size_t count) {
  return std::vector<VkDescriptorType>(count, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

// In 64 bits: groupCount would wrap for counts near 2^32.
uint32_t tileCount(uint32_t count) {
  return static_cast<uint32_t>((uint64_t{count} + RADIX_TILE - 1) / RADIX_TILE);
}

// One group per tile: the device's group-count limit (>= 65535, so >= 2^27 pairs) caps the pairs.
uint32_t checkedMaxCount(const Context& ctx, uint32_t maxCount) {
  const uint32_t maxGroups = ctx.properties().limits.maxComputeWorkGroupCount[0];
  if (tileCount(maxCount) > maxGroups)
    throw Error("radix sort: " + std::to_string(maxCount) + " pairs need more than the " +
                std::to_string(maxGroups) + " work groups the device allows");
  return maxCount;
}

}  // namespace

RadixSort::RadixSort(Context& ctx, uint32_t maxCount)
    : maxCount_(checkedMaxCount(ctx, maxCount)),
      histogram_(ctx, "radix_histogram", kRadixHistogramSpv, storageBindings(2),
                 sizeof(gpu::RadixSortPush)),
      scan_(ctx, "radix_scan", kRadixScanSpv, storageBindings(1), sizeof(gpu::RadixSortPush)),
      scatter_(ctx, "radix_scatter", kRadixScatterSpv, storageBindings(5),
               sizeof(gpu::RadixSortPush)),
      scratchKeys_(storageBuffer(ctx, VkDeviceSize{maxCount} * sizeof(uint32_t))),
      scratchValues_(storageBuffer(ctx, VkDeviceSize{maxCount} * sizeof(uint32_t))),
      table_(storageBuffer(ctx,
                           VkDeviceSize{tileCount(maxCount)} * RADIX_DIGITS * sizeof(uint32_t))) {}

void RadixSort::record(VkCommandBuffer cmd, const Buffer& keys, const Buffer& values,
                       uint32_t count, uint32_t keyBits, GpuProfiler* profiler,
                       const char* passName) const {
  if (keyBits < 1 || keyBits > 32)
    throw Error("radix sort: keyBits " + std::to_string(keyBits) + " is outside [1, 32]");
  if (count > maxCount_)
    throw Error("radix sort: " + std::to_string(count) + " pairs exceed the " +
                std::to_string(maxCount_) + " it was created for");
  assert(keys.size() >= VkDeviceSize{count} * sizeof(uint32_t));
  assert(values.size() >= VkDeviceSize{count} * sizeof(uint32_t));
  if (count < 2) return;  // already sorted

  ProfileScope scope(profiler, cmd, passName);
  const uint32_t tiles = tileCount(count);
  const uint32_t passes = groupCount(keyBits, RADIX_DIGIT_BITS);
  const Buffer* in[2] = {&keys, &values};
  const Buffer* out[2] = {&scratchKeys_, &scratchValues_};
  for (uint32_t pass = 0; pass < passes; ++pass) {
    const gpu::RadixSortPush push{count, pass * RADIX_DIGIT_BITS, tiles, 0};
    histogram_.dispatch(cmd, {Binding::storage(*in[0]), Binding::storage(table_)}, push, tiles);
    computeBarrier(cmd);
    scan_.dispatch(cmd, {Binding::storage(table_)}, push, 1);
    computeBarrier(cmd);
    scatter_.dispatch(cmd,
                      {Binding::storage(*in[0]), Binding::storage(*in[1]), Binding::storage(table_),
                       Binding::storage(*out[0]), Binding::storage(*out[1])},
                      push, tiles);
    std::swap(in, out);  // this pass's output is the next one's input
    if (pass + 1 < passes || in[0] == &keys) computeBarrier(cmd);
  }
  if (in[0] != &keys) {
    // An odd pass count leaves the pairs in the scratch buffers: copy them back. The barrier
    // before also orders the copy's writes after the last pass's reads of the caller's buffers.
    computeToTransferBarrier(cmd);
    const VkBufferCopy region{0, 0, VkDeviceSize{count} * sizeof(uint32_t)};
    vkCmdCopyBuffer(cmd, scratchKeys_.handle(), keys.handle(), 1, &region);
    vkCmdCopyBuffer(cmd, scratchValues_.handle(), values.handle(), 1, &region);
    transferToComputeBarrier(cmd);
  }
}

}  // namespace engine
