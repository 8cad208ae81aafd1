#version 460
// One view's weights for sharing the VSGLs (shaders/shared/vsgl_allocation.h): its attribute
// pyramids' top texels (the means of the luminance weights) and, with the BRSM PDF, the mean of
// its cells' view-importance term, recorded before the next view reuses the cells.
#extension GL_GOOGLE_include_directive : require

#include "shared/vsgl_allocation.h"

layout(local_size_x = 1) in;

layout(binding = 0, rgba32f) uniform readonly image2D diffusePowerTop;   // 1x1 mean
layout(binding = 1, rgba32f) uniform readonly image2D specularPowerTop;  // 1x1 mean
layout(binding = 2, rgba32f) uniform readonly image2D cellsTop;          // 1x1 mean (brsm only)
layout(std430, binding = 3) buffer Weights { VsglViewWeight weights[]; };
layout(push_constant) uniform Push { VsglViewWeightPush pc; };

void main() {
  float power = imageLoad(diffusePowerTop, ivec2(0)).a + imageLoad(specularPowerTop, ivec2(0)).a;
  float importance = pc.brsm != 0u ? imageLoad(cellsTop, ivec2(0)).b : power;
  weights[pc.view].weight = vec4(power, importance, 0.0, 0.0);
}
