// CPU twin of the mip pyramid in double: level l holds the exact mean of the 2^l x 2^l texels of
// level 0 under each texel (not a chain of rounded reductions), which is what the GPU's fp32
// reductions approximate.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace gi {

// levels[0] = `base` (size x size, row-major), levels[l] = (size >> l)^2 exact means.
std::vector<std::vector<glm::dvec4>> mipReference(const std::vector<glm::dvec4>& base,
                                                  uint32_t size);

}  // namespace gi
