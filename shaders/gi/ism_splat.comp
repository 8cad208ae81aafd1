#version 460
// ISM build, step 2 (shaders/shared/ism.h): one work group per VSGL splats the VSGL's subset of
// pool points, one texel each, into its tile of the atlas: the paraboloid texel of the point's
// direction from the ISM centre keeps the smallest distance (m) with a 32-bit atomicMin on the
// float's bits (order-preserving for non-negative floats), so the result does not depend on
// execution order. Points at or behind the hemisphere's base plane are dropped. The frame is
// the shared one of common/ism_lookup.glsl. CPU twin: ismSplatReference.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"
#include "shared/vsgl.h"
#define ISM_FRAME_ONLY
#include "common/ism_lookup.glsl"

layout(local_size_x = ISM_GROUP_SIZE) in;

layout(binding = 0, rgba32f) uniform readonly image2D positions;
layout(std430, binding = 1) readonly buffer Vsgls { Vsgl vsgls[]; };
layout(binding = 2, r32ui) uniform uimage2D atlas;  // level 0, cleared to ISM_EMPTY
layout(push_constant) uniform Push { IsmSplatPush pc; };

void main() {
  uint k = gl_WorkGroupID.x;
  IsmFrame f = ismFrame(vsgls[k], pc.params.centreOffset);
  if (!f.lit) return;  // a dark VSGL's tile stays empty (+inf after pull-push)
  uint size = pc.params.mapSize;
  ivec2 origin = ismTileOrigin(pc.params, k);
  uint offset = ISM_SUBSET_OFFSET(k, pc.stride);
  for (uint j = gl_LocalInvocationID.x; j < pc.pointsPerVsgl; j += ISM_GROUP_SIZE) {
    uint i = offset + j * pc.stride;
    vec4 p = imageLoad(positions, ivec2(i & (ISM_POSITIONS_WIDTH - 1u), i >> ISM_POSITIONS_SHIFT));
    if (p.w == 0.0) continue;
    vec3 d = p.xyz - f.centre;
    float along = dot(d, f.axis);
    if (!(along > 0.0)) continue;
    float dist = length(d);
    uvec2 texel = min(uvec2(ismParaboloid(f, d, dist, along) * float(size)), uvec2(size - 1u));
    imageAtomicMin(atlas, origin + ivec2(texel), floatBitsToUint(dist));
  }
}
