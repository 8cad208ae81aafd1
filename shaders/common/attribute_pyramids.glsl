// The six VSGL attribute pyramids (shaders/shared/vsgl_attributes.h) as bindings VSGL_ATTR_*,
// read with texelFetch; the PDF is the diffuse axis map's alpha. Shared by the passes that read
// them: filtered generation and the k-means passes.
#ifndef SHADERS_COMMON_ATTRIBUTE_PYRAMIDS_GLSL
#define SHADERS_COMMON_ATTRIBUTE_PYRAMIDS_GLSL

#include "shared/vsgl_attributes.h"

layout(binding = VSGL_ATTR_DIFFUSE_POWER) uniform sampler2D diffusePower;
layout(binding = VSGL_ATTR_DIFFUSE_POSITION) uniform sampler2D diffusePosition;
layout(binding = VSGL_ATTR_DIFFUSE_AXIS) uniform sampler2D diffuseAxis;
layout(binding = VSGL_ATTR_SPECULAR_POWER) uniform sampler2D specularPower;
layout(binding = VSGL_ATTR_SPECULAR_POSITION) uniform sampler2D specularPosition;
layout(binding = VSGL_ATTR_SPECULAR_AXIS) uniform sampler2D specularAxis;

float pdfTexel(ivec2 t, int level) { return texelFetch(diffuseAxis, t, level).w; }

#endif
