// The GPU radix sort (engine/radix_sort.h) against std::stable_sort, exactly: values are the
// input indices, so equal keys out of input order fail the comparison (stability), and guard
// words after the pairs catch writes past `count`. Since the stable order is unique, matching
// the CPU on every run is also the determinism check.
#include <algorithm>
#include <array>
#include <cstdio>
#include <numeric>
#include <random>

#include "engine/commands.h"
#include "engine/profiler.h"
#include "engine/radix_sort.h"
#include "gpu_fixture.h"

namespace {

constexpr uint32_t kGuardWords = 16;
constexpr uint32_t kGuard = 0xDEADBEEFu;

struct Pairs {
  std::vector<uint32_t> keys;
  std::vector<uint32_t> values;
};

// The CPU reference: (key, input index) pairs in std::stable_sort order.
Pairs stableSortReference(const std::vector<uint32_t>& keys) {
  Pairs out{{}, std::vector<uint32_t>(keys.size())};
  std::iota(out.values.begin(), out.values.end(), 0u);
  std::stable_sort(out.values.begin(), out.values.end(),
                   [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  for (uint32_t i : out.values) out.keys.push_back(keys[i]);
  return out;
}

std::vector<uint32_t> randomKeys(uint32_t count, uint32_t keyBits, uint32_t seed) {
  std::mt19937 rng(seed);
  const uint32_t mask = keyBits == 32 ? ~0u : (1u << keyBits) - 1u;
  std::vector<uint32_t> keys(count);
  for (uint32_t& k : keys) k = static_cast<uint32_t>(rng()) & mask;
  return keys;
}

class RadixSortTest : public testing_gpu::GpuTest {
 protected:
  // Sorts (keys, index) pairs on the GPU in one submission and reads them back.
  Pairs sortOnGpu(const engine::RadixSort& sort, const std::vector<uint32_t>& keys,
                  uint32_t keyBits, engine::GpuProfiler* profiler = nullptr) {
    const auto count = static_cast<uint32_t>(keys.size());
    std::vector<uint32_t> keyWords(keys), valueWords(count);
    std::iota(valueWords.begin(), valueWords.end(), 0u);
    keyWords.resize(count + kGuardWords, kGuard);
    valueWords.resize(count + kGuardWords, kGuard);
    const VkDeviceSize bytes = keyWords.size() * sizeof(uint32_t);
    engine::Buffer keyBuffer(ctx(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                             engine::MemoryUsage::GpuOnly);
    engine::Buffer valueBuffer(ctx(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               engine::MemoryUsage::GpuOnly);
    keyBuffer.upload(ctx(), keyWords.data(), bytes);
    valueBuffer.upload(ctx(), valueWords.data(), bytes);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      if (profiler) profiler->beginFrame(cmd);
      sort.record(cmd, keyBuffer, valueBuffer, count, keyBits, profiler);
      engine::computeToTransferBarrier(cmd);
    });
    Pairs out{keyBuffer.readbackAs<uint32_t>(ctx()), valueBuffer.readbackAs<uint32_t>(ctx())};
    for (uint32_t i = count; i < count + kGuardWords; ++i) {
      EXPECT_EQ(out.keys[i], kGuard) << "key guard word " << i - count << " overwritten";
      EXPECT_EQ(out.values[i], kGuard) << "value guard word " << i - count << " overwritten";
    }
    out.keys.resize(count);
    out.values.resize(count);
    return out;
  }

  void expectStableSort(const engine::RadixSort& sort, const std::vector<uint32_t>& keys,
                        uint32_t keyBits) {
    const Pairs gpu = sortOnGpu(sort, keys, keyBits);
    const Pairs cpu = stableSortReference(keys);
    EXPECT_EQ(gpu.keys, cpu.keys) << keys.size() << " keys of " << keyBits << " bits";
    EXPECT_EQ(gpu.values, cpu.values) << keys.size() << " values, " << keyBits << "-bit keys";
  }
};

// Counts around one tile (2048 pairs), partial threads and a partial last tile; key widths with an
// odd and an even number of 4-bit passes, and widths that are not a multiple of 4.
TEST_F(RadixSortTest, RandomKeysMatchStableSortForEveryWidthAndCount) {
  engine::RadixSort sort(ctx(), 4099);
  uint32_t seed = 1;
  for (uint32_t keyBits : {1u, 4u, 7u, 11u, 16u, 32u})
    for (uint32_t count : {0u, 1u, 255u, 256u, 257u, 2047u, 2048u, 2049u, 4099u})
      expectStableSort(sort, randomKeys(count, keyBits, seed++), keyBits);
}

// A k-means-sized input sorted four times by one RadixSort; the last three are timed (the first
// dispatches compile the pipelines on lavapipe).
TEST_F(RadixSortTest, LargeInputMatchesStableSortOnEveryRun) {
  const uint32_t count = 1u << 18, keyBits = 11;
  engine::RadixSort sort(ctx(), count);
  engine::GpuProfiler profiler(ctx(), 1);
  const std::vector<uint32_t> keys = randomKeys(count, keyBits, 2024);
  const Pairs cpu = stableSortReference(keys);
  std::vector<double> ms;
  for (int run = 0; run < 4; ++run) {
    const Pairs gpu = sortOnGpu(sort, keys, keyBits, &profiler);
    ASSERT_EQ(gpu.keys, cpu.keys) << "run " << run;
    ASSERT_EQ(gpu.values, cpu.values) << "run " << run;
    if (run > 0) ms.push_back(profiler.results().at(0).ms);
  }
  std::printf("radix sort of %u pairs, %u-bit keys: %.1f ms (median of %zu runs)\n", count, keyBits,
              engine::median(ms), ms.size());
}

TEST_F(RadixSortTest, ManyEqualKeysKeepInputOrder) {
  engine::RadixSort sort(ctx(), 20000);
  // Three distinct keys differing only in their high bits, so early passes see ties only.
  const std::array<uint32_t, 3> distinct{0x0000u, 0x8000u, 0xF000u};
  std::mt19937 rng(7);
  std::vector<uint32_t> threeKeys(20000);
  for (uint32_t& k : threeKeys) k = distinct[rng() % distinct.size()];
  expectStableSort(sort, threeKeys, 16);
  expectStableSort(sort, std::vector<uint32_t>(20000, 0xFFFFFFFFu), 32);
  expectStableSort(sort, std::vector<uint32_t>(3000, 0u), 5);
}

TEST_F(RadixSortTest, SortedAndReverseSortedInputs) {
  const uint32_t count = 5000, keyBits = 13;
  engine::RadixSort sort(ctx(), count);
  std::vector<uint32_t> ascending(count);
  for (uint32_t i = 0; i < count; ++i) ascending[i] = i / 3;  // runs of equal keys
  expectStableSort(sort, ascending, keyBits);
  std::vector<uint32_t> descending(ascending.rbegin(), ascending.rend());
  expectStableSort(sort, descending, keyBits);
}

// Bad arguments throw before anything is recorded, so no command buffer is needed.
TEST_F(RadixSortTest, BadArgumentsThrow) {
  engine::RadixSort sort(ctx(), 100);
  engine::Buffer keys(ctx(), 404, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  engine::Buffer values(ctx(), 404, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        engine::MemoryUsage::GpuOnly);
  EXPECT_THROW(sort.record(VK_NULL_HANDLE, keys, values, 101, 8), engine::Error);
  EXPECT_THROW(sort.record(VK_NULL_HANDLE, keys, values, 10, 0), engine::Error);
  EXPECT_THROW(sort.record(VK_NULL_HANDLE, keys, values, 10, 33), engine::Error);
  engine::RadixSort empty(ctx(), 0);
  EXPECT_NO_THROW(empty.record(VK_NULL_HANDLE, keys, values, 0, 8));  // nothing to record
  EXPECT_THROW(empty.record(VK_NULL_HANDLE, keys, values, 1, 8), engine::Error);
}

}  // namespace
