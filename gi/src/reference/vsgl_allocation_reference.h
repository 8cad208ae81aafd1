// CPU twin of vsgl_allocate.comp (shaders/shared/vsgl_allocation.h): each RSM view's share of the
// frame's N VSGLs, in the shader's fp32 arithmetic and order, so that the two agree exactly.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace gi {

// weights[v] = (mean reflected power, mean view importance) of view v (VsglViewWeight.xy);
// returns (first record, count) per view, the counts adding up to `count`.
std::vector<glm::uvec2> allocateVsglsReference(std::span<const glm::vec2> weights, float fluxMix,
                                               uint32_t count);

}  // namespace gi
