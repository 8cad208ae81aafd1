#version 460
// k-means: each cluster's range [start, end) in the sorted (cluster, texel) pairs, one thread per
// pair, found where the key changes; the ranges start zeroed, so an empty cluster reads (0, 0).
#extension GL_GOOGLE_include_directive : require

#include "shared/kmeans.h"

layout(local_size_x = KMEANS_BOUNDS_GROUP) in;

layout(std430, binding = 0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = 1) writeonly buffer Ranges { uvec2 ranges[]; };
layout(push_constant) uniform Push { KmeansPush pc; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.texelCount) return;
  uint k = keys[i];
  if (k >= pc.clusters) return;
  if (i == 0u || keys[i - 1u] != k) ranges[k].x = i;
  if (i + 1u == pc.texelCount || keys[i + 1u] != k) ranges[k].y = i + 1u;
}
