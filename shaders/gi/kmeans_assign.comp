#version 460
// k-means assignment (shaders/shared/kmeans.h), one thread per RSM texel: the nearest centre by
// squared distance (ties to the lower index), written as the (cluster, texel) pair the radix sort
// orders; an unpowered texel gets cluster K. Each cluster's member count and its costliest
// member (weight x squared distance, ties to the lower texel) are gathered with integer atomics
// for kmeans_fill: counts and maxima do not depend on the order the atomics land in, so the
// pass is deterministic. CPU twin: gi::assignReference.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "common/kmeans_texel.glsl"

layout(local_size_x = KMEANS_ASSIGN_GROUP) in;

layout(std430, binding = VSGL_ATTR_COUNT) readonly buffer Centres { vec4 centres[]; };
layout(std430, binding = VSGL_ATTR_COUNT + 1) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = VSGL_ATTR_COUNT + 2) writeonly buffer Values { uint values[]; };
layout(std430, binding = VSGL_ATTR_COUNT + 3) buffer Counts { uint counts[]; };
// (cost bits << 32) | (0xffffffff - texel): non-negative floats order like their bits, and the
// complement makes the lower texel win a tie. 0 = no member.
layout(std430, binding = VSGL_ATTR_COUNT + 4) buffer Costliest { uint64_t costliest[]; };
layout(push_constant) uniform Push { KmeansPush pc; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  // Every lane runs the centre loop, out-of-range texels included, so that each broadcast
  // reads an active lane: centres reach the lanes through registers, one block of subgroup size
  // at a time (as in vsgl_shade.comp; lavapipe loads per lane even at a uniform address).
  bool inside = i < pc.texelCount;
  KmeansTexel t = kmeansTexel(min(i, pc.texelCount - 1u), pc.size, pc.space, pc.weighting);
  float best = uintBitsToFloat(0x7f800000u);  // +inf
  uint nearest = 0u;
  uint lanes = subgroupBallotBitCount(subgroupBallot(true));
  for (uint first = 0u; first < pc.clusters; first += lanes) {
    uint count = min(lanes, pc.clusters - first);
    vec3 mine = centres[first + min(gl_SubgroupInvocationID, count - 1u)].xyz;
    for (uint lane = 0u; lane < count; ++lane) {
      vec3 d = t.feature - subgroupBroadcast(mine, lane);
      float distance2 = dot(d, d);
      if (distance2 < best) {
        best = distance2;
        nearest = first + lane;
      }
    }
  }
  if (!inside) return;
  values[i] = i;
  if (!t.powered) {
    keys[i] = pc.clusters;
    return;
  }
  keys[i] = nearest;
  atomicAdd(counts[nearest], 1u);
  uint64_t cost = uint64_t(floatBitsToUint(t.weight * best)) << 32;
  atomicMax(costliest[nearest], cost | uint64_t(0xffffffffu - i));
}
