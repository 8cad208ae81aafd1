#version 460
// k-means empty-cluster rule (shaders/shared/kmeans.h), by ONE work group after the assignment:
// each empty cluster, in index order, takes the costliest member of the donor whose costliest
// member costs most (ties: lower cluster), among clusters with at least two members, one texel
// per donor. Each round is two reductions over the clusters in a fixed order (deterministic);
// with no empty cluster, the usual case, the pass ends after one count. The number filled goes
// to stats[iteration]. CPU twin: gi::fillEmptyClustersReference.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/kmeans.h"

layout(local_size_x = KMEANS_FILL_GROUP) in;

layout(std430, binding = 0) buffer Keys { uint keys[]; };
layout(std430, binding = 1) buffer Counts { uint counts[]; };
layout(std430, binding = 2) buffer Costliest { uint64_t costliest[]; };
layout(std430, binding = 3) buffer Stats { uint stats[]; };
layout(push_constant) uniform Push { KmeansPush pc; };

const uint kNone = 0xffffffffu;

shared uint emptyCount;
shared uint firstEmpty[KMEANS_FILL_GROUP];
shared uint64_t donorCost[KMEANS_FILL_GROUP];
shared uint donor[KMEANS_FILL_GROUP];

// Whether donor a (cost ca) ranks before donor b: higher cost first, then the lower index.
bool before(uint64_t ca, uint a, uint64_t cb, uint b) {
  return b == kNone || (a != kNone && (ca > cb || (ca == cb && a < b)));
}

void main() {
  uint g = gl_LocalInvocationID.x;
  if (g == 0u) emptyCount = 0u;
  barrier();
  uint mine = 0u;
  for (uint k = g; k < pc.clusters; k += KMEANS_FILL_GROUP) mine += counts[k] == 0u ? 1u : 0u;
  atomicAdd(emptyCount, mine);
  barrier();
  uint rounds = emptyCount;
  uint filled = 0u;
  for (uint round = 0u; round < rounds; ++round) {
    // The lowest empty cluster and the best donor, each thread over its strided share.
    uint empty = kNone, best = kNone;
    uint64_t bestCost = 0ul;
    for (uint k = g; k < pc.clusters; k += KMEANS_FILL_GROUP) {
      uint n = counts[k];
      if (n == 0u && empty == kNone) empty = k;
      // A used donor has costliest = 0: its next costliest member is unknown this iteration.
      uint64_t c = costliest[k];
      if (n >= 2u && c != 0ul && before(c >> 32, k, bestCost, best)) {
        best = k;
        bestCost = c >> 32;
      }
    }
    firstEmpty[g] = empty;
    donor[g] = best;
    donorCost[g] = bestCost;
    barrier();
    for (uint offset = KMEANS_FILL_GROUP / 2u; offset > 0u; offset >>= 1u) {
      if (g < offset) {
        firstEmpty[g] = min(firstEmpty[g], firstEmpty[g + offset]);
        if (before(donorCost[g + offset], donor[g + offset], donorCost[g], donor[g])) {
          donor[g] = donor[g + offset];
          donorCost[g] = donorCost[g + offset];
        }
      }
      barrier();
    }
    uint e = firstEmpty[0], d = donor[0];
    if (e == kNone || d == kNone) break;  // no donor left: the rest stay empty
    if (g == 0u) {
      uint texel = 0xffffffffu - uint(costliest[d] & 0xfffffffful);
      keys[texel] = e;
      counts[d] -= 1u;
      counts[e] = 1u;
      costliest[d] = 0ul;
    }
    ++filled;
    memoryBarrierBuffer();
    barrier();
  }
  if (g == 0u) stats[pc.iteration] = filled;
}
