#version 460
// 2x2 box reduction of one mip level of an RGBA32F pyramid (see shaders/shared/mip_reduce.h).
// The CPU twin is gi/src/reference/mip_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/mip_reduce.h"

layout(local_size_x = MIP_GROUP_X, local_size_y = MIP_GROUP_Y) in;

layout(binding = 0, rgba32f) uniform readonly image2D src;
layout(binding = 1, rgba32f) uniform writeonly image2D dst;
layout(push_constant) uniform Push { MipReducePush pc; };

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, pc.dstSize))) return;
  ivec2 s = ivec2(texel) * 2;
  // Pairwise sums, then a scale by an exact power of two: the same rounding as the reference.
  vec4 top = imageLoad(src, s) + imageLoad(src, s + ivec2(1, 0));
  vec4 bottom = imageLoad(src, s + ivec2(0, 1)) + imageLoad(src, s + ivec2(1, 1));
  imageStore(dst, ivec2(texel), (top + bottom) * 0.25);
}
