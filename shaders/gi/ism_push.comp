#version 460
// ISM build, step 3b (shaders/shared/ism.h): the push half of pull-push. One dispatch per level
// l = log2 S - 1..0, from the top down; an empty texel of level l takes the bilinear
// interpolation of level l + 1 (complete by then) at its centre: weights 3/4 and 1/4 per axis,
// taps clamped to the tile so that no VSGL's map bleeds into another's. A tile without any
// point stays empty up the pyramid and becomes +inf at level 0: nothing occludes.
// One thread per 2 x 2 block of level l: the block's four texels share the 3 x 3 texels of
// level l + 1 around their parent, loaded once. (llvmpipe pays per invocation and per lane of
// every memory access, masked or not, so this halves the work of one thread per texel.)
// CPU twin: ismPullPushReference.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"

layout(local_size_x = ISM_IMAGE_GROUP, local_size_y = ISM_IMAGE_GROUP) in;

layout(binding = 0, r32ui) uniform readonly uimage2D coarser;  // level l + 1, complete
layout(binding = 1, r32ui) uniform uimage2D target;            // level l
layout(push_constant) uniform Push { IsmPullPushPush pc; };

void main() {
  uvec2 parent = gl_GlobalInvocationID.xy;  // texel of level l + 1
  if (any(greaterThanEqual(2u * parent, pc.size))) return;
  // The parent's tile at level l + 1: side 2^(tileShift - 1), first texel `lo`.
  ivec2 lo = ivec2((parent >> (pc.tileShift - 1u)) << (pc.tileShift - 1u));
  ivec2 hi = lo + int((1u << (pc.tileShift - 1u)) - 1u);
  float c[3][3];
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x)
      c[y][x] = uintBitsToFloat(imageLoad(coarser, clamp(ivec2(parent) + ivec2(x, y) - 1, lo, hi)).r);
  bool emptyTile = floatBitsToUint(c[1][1]) == ISM_EMPTY;  // then all nine are empty
  uint fill = emptyTile ? (pc.level == 0u ? ISM_INFINITY : ISM_EMPTY) : 0u;
  for (uint q = 0u; q < 4u; ++q) {
    uvec2 o = uvec2(q & 1u, q >> 1u);
    ivec2 t = ivec2(2u * parent + o);
    // Fine texel 2m + o sits at coarse m - 1/4 (o = 0) or m + 1/4 (o = 1): taps m - 1 + o and
    // m + o (indices o, o + 1 of the 3 x 3), weight 3/4 on the nearer.
    vec2 w = mix(vec2(0.75), vec2(0.25), bvec2(o));  // weight of the second tap
    float bottom = mix(c[o.y][o.x], c[o.y][o.x + 1u], w.x);
    float top = mix(c[o.y + 1u][o.x], c[o.y + 1u][o.x + 1u], w.x);
    uint bits = emptyTile ? fill : floatBitsToUint(mix(bottom, top, w.y));
    if (imageLoad(target, t).r == ISM_EMPTY) imageStore(target, t, uvec4(bits));
  }
}
