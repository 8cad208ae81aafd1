// Push constants of vsgl_attributes.comp.
#ifndef SHADERS_SHARED_VSGL_ATTRIBUTES_PASS_H
#define SHADERS_SHARED_VSGL_ATTRIBUTES_PASS_H
#include "interop.h"

SHARED_BEGIN

struct VsglAttributesPush {
  vec4 axis;              // xyz = unit direction the light travels (used for directional lights)
  uvec2 size;             // RSM texels (a power-of-two square)
  uint perspective;       // 1 = spot: the direction to the light is -normalize(y)
  uint broadReflections;  // 1: broad reflections join the diffuse lobe (vplGlossyShare)
};

SHARED_END

SHARED_ASSERT_SIZE(VsglAttributesPush, 32);
#endif
