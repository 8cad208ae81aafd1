#include "reference/vsgl_allocation_reference.h"

#include <algorithm>
#include <cmath>

namespace gi {

std::vector<glm::uvec2> allocateVsglsReference(std::span<const glm::vec2> weights, float fluxMix,
                                               uint32_t count) {
  const size_t views = weights.size();
  float sumX = 0.0f, sumY = 0.0f;
  for (const glm::vec2& w : weights) {
    sumX += w.x;
    sumY += w.y;
  }
  const float m = sumY > 0.0f ? fluxMix : 1.0f;
  std::vector<float> exact(views);
  std::vector<uint32_t> counts(views);
  uint32_t given = 0;
  for (size_t v = 0; v < views; ++v) {
    const glm::vec2 w = weights[v];
    const float share = sumX > 0.0f
                            ? (1.0f - m) * (sumY > 0.0f ? w.y / sumY : 0.0f) + m * w.x / sumX
                            : 1.0f / float(views);
    exact[v] = share * float(count);
    counts[v] = std::min(static_cast<uint32_t>(std::floor(exact[v])), count);
    given += counts[v];
  }
  while (given < count) {
    size_t best = 0;
    float bestRemainder = -1.0f;
    for (size_t v = 0; v < views; ++v) {
      const float remainder = exact[v] - float(counts[v]);
      if (remainder > bestRemainder) {
        bestRemainder = remainder;
        best = v;
      }
    }
    counts[best] += 1;
    exact[best] = float(counts[best]) - 1.0f;
    ++given;
  }
  while (given > count) {
    const size_t largest = size_t(std::max_element(counts.begin(), counts.end()) - counts.begin());
    counts[largest] -= 1;
    --given;
  }
  std::vector<glm::uvec2> ranges(views);
  for (uint32_t v = 0, first = 0; v < views; ++v) {
    ranges[v] = {first, counts[v]};
    first += counts[v];
  }
  return ranges;
}

}  // namespace gi
