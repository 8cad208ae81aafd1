// The GGX specular albedo table of shaders/common/sg_lighting.glsl (ggxSpecularAlbedo) as the
// storage buffer its includers bind: vec2[17 x 17] of gi::ggxSpecularAlbedoNode, in host-visible
// memory written at creation (no submit). A constant GLSL array indexed at run time is rebuilt
// per invocation on lavapipe, hence a buffer.
#pragma once

#include "engine/buffer.h"
#include "engine/vk_context.h"

namespace gi {

engine::Buffer createGgxAlbedoTable(engine::Context& ctx);

}  // namespace gi
