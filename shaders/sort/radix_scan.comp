#version 460
// Radix sort, step 2 of a pass (shaders/shared/radix_sort.h): exclusive prefix sum of the
// digit-major table (RADIX_DIGITS x tileCount counts) in place, by ONE work group so the order
// of every addition is fixed, as in gi/ism_scan.comp: thread g owns the contiguous chunk
// [g c, (g + 1) c), c = ceil(size / RADIX_SCAN_GROUP); it sums its chunk, a Hillis-Steele scan
// over the chunk sums in shared memory gives each thread its starting offset, and the thread
// rewrites its chunk as running offsets. Afterwards table[d * tileCount + tile] is the output
// index of the tile's first element with digit d. The table is small (16 counts per 2048
// elements: 32 Ki counts for 2^22 pairs), so one group is a small share of a pass.
#extension GL_GOOGLE_include_directive : require

#include "shared/radix_sort.h"

layout(local_size_x = RADIX_SCAN_GROUP) in;

layout(std430, binding = 0) buffer Table { uint table[]; };
layout(push_constant) uniform Push { RadixSortPush pc; };

shared uint chunkSums[RADIX_SCAN_GROUP];

void main() {
  uint g = gl_LocalInvocationID.x;
  uint size = RADIX_DIGITS * pc.tileCount;
  uint chunk = (size + RADIX_SCAN_GROUP - 1u) / RADIX_SCAN_GROUP;
  uint begin = min(g * chunk, size);
  uint end = min(begin + chunk, size);
  uint sum = 0u;
  for (uint i = begin; i < end; ++i) sum += table[i];
  chunkSums[g] = sum;
  barrier();
  for (uint offset = 1u; offset < RADIX_SCAN_GROUP; offset <<= 1u) {
    uint add = g >= offset ? chunkSums[g - offset] : 0u;
    barrier();
    chunkSums[g] += add;
    barrier();
  }
  uint running = g > 0u ? chunkSums[g - 1u] : 0u;
  for (uint i = begin; i < end; ++i) {
    uint countHere = table[i];
    table[i] = running;
    running += countHere;
  }
}
