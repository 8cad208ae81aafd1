// CPU twin of gbuffer_convert.comp (shaders/shared/gbuffer_convert.h), in double: a host's depth
// and normal encodings turned into the module's forward NDC depth and octahedral normal.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

namespace gi {

// Forward NDC depth (1 = sky) of a stored depth value in GBUFFER_DEPTH_* `encoding`; depthRow as
// GBufferConvertPush::depthRow. A result outside [0, 1) or non-finite is the sky's 1.
double forwardDepthReference(uint32_t encoding, double stored, glm::dvec4 depthRow);
// The octahedral encoding (common/octahedral.glsl) of a stored normal in GBUFFER_NORMAL_*
// `encoding`; (0, 0) for a zero normal. The pass writes (0, 0) wherever the forward depth is the
// sky's (>= 1), whatever the stored normal.
glm::dvec2 octahedralReference(uint32_t encoding, glm::dvec4 stored);

}  // namespace gi
