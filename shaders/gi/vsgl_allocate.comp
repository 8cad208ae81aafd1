#version 460
// Each view's share of the N VSGLs (shaders/shared/vsgl_allocation.h), one thread: the view's
// part of the frame's sampling weight, (1 - m) y / sum y + m x / sum x as the PDF mixes the BRSM
// with the flux (m = 1 with the flux PDF), times N, rounded by largest remainder (ties to the
// lower view) so that the counts add up to N; ranges follow in view order. Without any power
// every view gets an equal share (their records all carry zero power). The CPU twin is
// allocateVsglsReference, in the same fp32 arithmetic.
#extension GL_GOOGLE_include_directive : require

#include "shared/vsgl_allocation.h"

layout(local_size_x = 1) in;

layout(std430, binding = 0) readonly buffer Weights { VsglViewWeight weights[]; };
layout(std430, binding = 1) writeonly buffer Ranges { VsglViewRange ranges[]; };
layout(push_constant) uniform Push { VsglAllocatePush pc; };

void main() {
  uint views = min(pc.viewCount, VSGL_MAX_VIEWS);
  float sumX = 0.0, sumY = 0.0;
  for (uint v = 0u; v < views; ++v) {
    sumX += weights[v].weight.x;
    sumY += weights[v].weight.y;
  }
  // m = 1 where the BRSM saw nothing: the flux alone.
  float m = sumY > 0.0 ? pc.fluxMix : 1.0;
  float exact[VSGL_MAX_VIEWS];
  uint counts[VSGL_MAX_VIEWS];
  uint given = 0u;
  for (uint v = 0u; v < views; ++v) {
    vec2 w = weights[v].weight.xy;
    float share = sumX > 0.0 ? (1.0 - m) * (sumY > 0.0 ? w.y / sumY : 0.0) + m * w.x / sumX
                             : 1.0 / float(views);
    exact[v] = share * float(pc.count);
    counts[v] = min(uint(floor(exact[v])), pc.count);
    given += counts[v];
  }
  // Largest remainders first; a view is never given a second extra record.
  while (given < pc.count) {
    uint best = 0u;
    float bestRemainder = -1.0;
    for (uint v = 0u; v < views; ++v) {
      float remainder = exact[v] - float(counts[v]);
      if (remainder > bestRemainder) {
        bestRemainder = remainder;
        best = v;
      }
    }
    counts[best] += 1u;
    exact[best] = float(counts[best]) - 1.0;  // remainder now below every other's
    ++given;
  }
  // Rounding of the shares can over-give by a record or two: take them from the largest.
  while (given > pc.count) {
    uint largest = 0u;
    for (uint v = 1u; v < views; ++v)
      if (counts[v] > counts[largest]) largest = v;
    counts[largest] -= 1u;
    --given;
  }
  uint first = 0u;
  for (uint v = 0u; v < views; ++v) {
    ranges[v].range = uvec4(first, counts[v], 0u, 0u);
    first += counts[v];
  }
}
