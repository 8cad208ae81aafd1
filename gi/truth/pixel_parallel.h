// Pixel loops of the CPU references spread over threads. Each pixel's work must depend only on
// the pixel (its own random stream), so results do not depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace truth {

// 0 = every core.
inline unsigned threadCount(unsigned requested) {
  return requested > 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
}

// Runs `work(pixel)` over every pixel on `threads` threads, pixels handed out in chunks.
template <class Work>
void forEachPixel(size_t pixels, unsigned threads, Work work) {
  std::atomic<size_t> next{0};
  constexpr size_t kChunk = 16;
  auto worker = [&] {
    for (size_t first; (first = next.fetch_add(kChunk)) < pixels;)
      for (size_t i = first; i < std::min(first + kChunk, pixels); ++i) work(i);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace truth
