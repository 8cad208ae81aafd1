#version 460
// Radix sort, step 1 of a pass (shaders/shared/radix_sort.h): the 16 digit counts of one tile,
// written digit-major into the table. Counts are integer sums, the same whatever order the
// additions happen in, so shared-memory atomicAdd is deterministic here (it is the ranking in
// radix_scatter.comp that must not depend on order). On lavapipe every shared-memory access is
// a scalar operation per lane, and one atomic per element took half the instructions of
// per-thread packed counters summed in a fixed order (measured with callgrind). Thread t takes
// the elements t, t + RADIX_GROUP, ... so that neighbouring threads read neighbouring keys.
#extension GL_GOOGLE_include_directive : require

#include "shared/radix_sort.h"

layout(local_size_x = RADIX_GROUP) in;

layout(std430, binding = 0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = 1) writeonly buffer Table { uint table[]; };
layout(push_constant) uniform Push { RadixSortPush pc; };

shared uint counts[RADIX_DIGITS];

void main() {
  uint t = gl_LocalInvocationID.x;
  uint tileBase = gl_WorkGroupID.x * RADIX_TILE;
  if (t < RADIX_DIGITS) counts[t] = 0u;
  barrier();
  for (uint k = 0u; k < RADIX_ITEMS; ++k) {
    uint i = tileBase + k * RADIX_GROUP + t;
    if (i < pc.count) atomicAdd(counts[(keys[i] >> pc.shift) & RADIX_DIGIT_MASK], 1u);
  }
  barrier();
  if (t < RADIX_DIGITS) table[t * pc.tileCount + gl_WorkGroupID.x] = counts[t];
}
