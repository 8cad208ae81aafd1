// The directional albedo of brdf.glsl's GGX specular lobe at 17 x 17 nodes, the table both the
// shading passes (a storage buffer, passes/ggx_albedo_table.h) and the CPU twins
// (reference/sg_math.h, ggxSpecularAlbedo) read.
#pragma once

#include <glm/glm.hpp>

namespace gi {

// Node (i, j), 0 <= i, j < kGgxAlbedoTableSize, at n . v = max((i / 16)^2, 1e-4) and
// alpha = max((j / 16)^2, 1e-3): the albedo with f0 = 0 (x) and with f0 = 1 (y).
constexpr int kGgxAlbedoTableSize = 17;
glm::dvec2 ggxSpecularAlbedoNode(int i, int j);

}  // namespace gi
