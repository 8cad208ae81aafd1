#version 460
// k-means assignment (shaders/shared/kmeans.h), KMEANS_ASSIGN_TEXELS RSM texels per thread: the
// nearest centre by squared distance (ties to the lower index), written as the (cluster, texel)
// pair the radix sort orders; an unpowered texel gets cluster K. Each cluster's member count
// and its costliest member (weight x squared distance, ties to the lower texel) are gathered
// with integer atomics for kmeans_fill: counts and maxima do not depend on the order the
// atomics land in, so the pass is deterministic. CPU twin: gi::assignReference.
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
  // Each thread assigns KMEANS_ASSIGN_TEXELS texels, so one broadcast centre serves that many
  // distance tests (register blocking). Measured on lavapipe at RSM 512^2 and 1024 centres, one
  // iteration: 1.1-1.4 s with one texel per thread, 0.35-0.45 s with 4, 0.17-0.18 s with 16
  // (0.65 ns per texel-centre pair, about 2x the FMA peak's bound), no clear gain at 32.
  uint base = gl_GlobalInvocationID.x * KMEANS_ASSIGN_TEXELS;
  KmeansTexel t[KMEANS_ASSIGN_TEXELS];
  float best[KMEANS_ASSIGN_TEXELS];
  uint nearest[KMEANS_ASSIGN_TEXELS];
  for (uint j = 0u; j < KMEANS_ASSIGN_TEXELS; ++j) {
    t[j] = kmeansTexel(min(base + j, pc.texelCount - 1u), pc.size, pc.space, pc.weighting);
    best[j] = uintBitsToFloat(0x7f800000u);  // +inf
    nearest[j] = 0u;
  }
  // Every lane runs the centre loop, out-of-range texels included, so that each broadcast
  // reads an active lane: centres reach the lanes through registers, one block of subgroup size
  // at a time (as in vsgl_shade.comp; lavapipe loads per lane even at a uniform address).
  uint lanes = subgroupBallotBitCount(subgroupBallot(true));
  for (uint first = 0u; first < pc.clusters; first += lanes) {
    uint count = min(lanes, pc.clusters - first);
    vec3 mine = centres[first + min(gl_SubgroupInvocationID, count - 1u)].xyz;
    for (uint lane = 0u; lane < count; ++lane) {
      vec3 c = subgroupBroadcast(mine, lane);
      for (uint j = 0u; j < KMEANS_ASSIGN_TEXELS; ++j) {
        vec3 d = t[j].feature - c;
        float distance2 = dot(d, d);
        if (distance2 < best[j]) {
          best[j] = distance2;
          nearest[j] = first + lane;
        }
      }
    }
  }
  for (uint j = 0u; j < KMEANS_ASSIGN_TEXELS; ++j) {
    uint i = base + j;
    if (i >= pc.texelCount) return;
    values[i] = i;
    if (!t[j].powered) {
      keys[i] = pc.clusters;
      continue;
    }
    keys[i] = nearest[j];
    atomicAdd(counts[nearest[j]], 1u);
    uint64_t cost = uint64_t(floatBitsToUint(t[j].weight * best[j])) << 32;
    atomicMax(costliest[nearest[j]], cost | uint64_t(0xffffffffu - i));
  }
}
