#include "reference/mip_reference.h"

namespace gi {

std::vector<std::vector<glm::dvec4>> mipReference(const std::vector<glm::dvec4>& base,
                                                  uint32_t size) {
  std::vector<std::vector<glm::dvec4>> levels{base};
  for (uint32_t block = 2; block <= size; block *= 2) {
    uint32_t n = size / block;
    std::vector<glm::dvec4> level(size_t{n} * n, glm::dvec4(0.0));
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x)
        level[size_t{y / block} * n + x / block] += base[size_t{y} * size + x];
    for (glm::dvec4& v : level) v /= double(block) * block;
    levels.push_back(std::move(level));
  }
  return levels;
}

}  // namespace gi
