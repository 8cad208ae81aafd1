#version 460
// ISM points, step 2 (shaders/shared/ism.h): inclusive prefix sum of the triangle areas, in
// place, by ONE work group, so the order of every addition is fixed (deterministic, no atomics):
// thread g owns the contiguous chunk [g c, (g + 1) c), c = ceil(T / ISM_SCAN_GROUP); it sums
// its chunk in order, a Hillis-Steele scan over the chunk sums in shared memory gives each
// thread its starting value, and the thread rewrites its chunk as running sums. One group is
// enough: this runs once per scene change and reads one float per triangle.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"

layout(local_size_x = ISM_SCAN_GROUP) in;

layout(std430, binding = 0) buffer Cdf { float cdf[]; };
layout(push_constant) uniform Push { IsmAreaPush pc; };

shared float chunkSums[ISM_SCAN_GROUP];

void main() {
  uint g = gl_LocalInvocationID.x;
  uint chunk = (pc.triangleCount + ISM_SCAN_GROUP - 1u) / ISM_SCAN_GROUP;
  uint begin = min(g * chunk, pc.triangleCount);
  uint end = min(begin + chunk, pc.triangleCount);
  float sum = 0.0;
  for (uint t = begin; t < end; ++t) sum += cdf[t];
  chunkSums[g] = sum;
  barrier();
  for (uint offset = 1u; offset < ISM_SCAN_GROUP; offset <<= 1u) {
    float add = g >= offset ? chunkSums[g - offset] : 0.0;
    barrier();
    chunkSums[g] += add;
    barrier();
  }
  float running = g > 0u ? chunkSums[g - 1u] : 0.0;
  for (uint t = begin; t < end; ++t) {
    running += cdf[t];
    cdf[t] = running;
  }
}
