// CPU twin of vsgl_attributes.comp, in double: level 0 of the six attribute pyramids from the
// RSM's own images (read back from the GPU, so both sides start from identical inputs).
#pragma once

#include <array>
#include <vector>

#include "common/rsm_view.h"
#include "engine/gbuffer_reference.h"
#include "shared/vsgl_attributes.h"

namespace gi {

struct RsmImages {
  std::vector<glm::vec4> position;  // ReflectiveShadowMap::position(), level 0
  std::vector<glm::vec4> diffuse;   // ::diffuseFlux()
  std::vector<glm::vec4> specular;  // ::specularFlux()
  engine::GBufferData surface;      // the light's G-buffer (normals)
};

// broadReflections: a texel's broad reflection joins its diffuse lobe (gi::glossyShare), as
// Settings::broadReflections; false keeps every reflection in the specular lobe.
std::array<std::vector<glm::dvec4>, VSGL_ATTR_COUNT> vsglAttributesReference(
    const RsmImages& rsm, const RsmView& view, bool broadReflections = false);

}  // namespace gi
