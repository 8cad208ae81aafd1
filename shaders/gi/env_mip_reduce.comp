#version 460
// 2x2 box reduction of one mip level of the 2-layer environment map (shared/environment.h),
// both layers in one dispatch (z = layer). The same rounding as shaders/gi/mip_reduce.comp:
// pairwise sums, then an exact scale by 1/4. CPU twin: gi/src/reference/env_map_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/env_map.h"

layout(local_size_x = ENV_MIP_GROUP_X, local_size_y = ENV_MIP_GROUP_Y) in;

layout(binding = 0, rgba32f) uniform readonly image2DArray src;
layout(binding = 1, rgba32f) uniform writeonly image2DArray dst;
layout(push_constant) uniform Push { EnvMipPush pc; };

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (any(greaterThanEqual(id.xy, pc.dstSize)) || id.z >= 2u) return;
  ivec3 s = ivec3(ivec2(id.xy) * 2, int(id.z));
  vec4 top = imageLoad(src, s) + imageLoad(src, s + ivec3(1, 0, 0));
  vec4 bottom = imageLoad(src, s + ivec3(0, 1, 0)) + imageLoad(src, s + ivec3(1, 1, 0));
  imageStore(dst, ivec3(id), (top + bottom) * 0.25);
}
