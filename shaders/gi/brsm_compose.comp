#version 460
// BRSM PDF at level 0 (shaders/shared/brsm.h): each texel's weights times its cell's importance,
// mixed with the flux PDF, written to the alpha of the diffuse axis pyramid (which the caller
// then mip-maps again). The CPU twin is gi/src/reference/brsm_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/brsm.h"

layout(local_size_x = BRSM_GROUP_X, local_size_y = BRSM_GROUP_Y) in;

layout(binding = 0, rgba32f) uniform readonly image2D diffusePower;      // level 0
layout(binding = 1, rgba32f) uniform readonly image2D specularPower;     // level 0
layout(binding = 2, rgba32f) uniform readonly image2D diffusePowerTop;   // 1x1 mean
layout(binding = 3, rgba32f) uniform readonly image2D specularPowerTop;  // 1x1 mean
layout(binding = 4, rgba32f) uniform readonly image2D cells;             // level 0
layout(binding = 5, rgba32f) uniform readonly image2D cellsTop;          // 1x1 mean
layout(binding = 6, rgba32f) uniform image2D diffuseAxis;                // level 0, alpha = PDF
layout(push_constant) uniform Push { BrsmComposePush pc; };

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, uvec2(pc.size)))) return;
  ivec2 t = ivec2(texel);
  float wd = imageLoad(diffusePower, t).a;
  float ws = imageLoad(specularPower, t).a;
  float meanW = imageLoad(diffusePowerTop, ivec2(0)).a + imageLoad(specularPowerTop, ivec2(0)).a;
  float meanB = imageLoad(cellsTop, ivec2(0)).b;
  vec4 importance = imageLoad(cells, ivec2(texel >> pc.shift));
  float flux = meanW > 0.0 ? (wd + ws) / meanW : 0.0;
  float brsm = meanB > 0.0 ? (importance.r * wd + importance.g * ws) / meanB : flux;
  vec4 axis = imageLoad(diffuseAxis, t);
  imageStore(diffuseAxis, t, vec4(axis.xyz, mix(brsm, flux, pc.fluxMix)));
}
