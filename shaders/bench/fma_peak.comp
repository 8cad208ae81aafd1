#version 460
// FMA throughput (shaders/shared/fma_peak.h). The chains start from the thread index so every
// thread computes something different, and the loop bound comes from a push constant so the
// compiler cannot fold it. CPU twin: engine/src/machine_peak.cpp (fmaPeakReference).
#extension GL_GOOGLE_include_directive : require

#include "shared/fma_peak.h"

layout(local_size_x = FMA_PEAK_GROUP) in;
layout(std430, binding = 0) writeonly buffer Out { float results[]; };
layout(push_constant) uniform Push { FmaPeakPush pc; };

// The 8 chains live in two vec4 registers: an array indexed in a loop would sit in private
// memory on lavapipe and measure loads and stores instead of arithmetic.
void main() {
  uint id = gl_GlobalInvocationID.x;
  vec4 x0 = float(id % 1024u) * 1e-3 + vec4(0.0, 1.0, 2.0, 3.0);
  vec4 x1 = float(id % 1024u) * 1e-3 + vec4(4.0, 5.0, 6.0, 7.0);
  vec4 a = vec4(pc.a), b = vec4(pc.b);
  // Unrolled by 4 so the loop's compare and branch are a small share of the work.
  uint i = 0u;
  for (; i + 4u <= pc.iterations; i += 4u) {
    x0 = fma(x0, a, b);
    x1 = fma(x1, a, b);
    x0 = fma(x0, a, b);
    x1 = fma(x1, a, b);
    x0 = fma(x0, a, b);
    x1 = fma(x1, a, b);
    x0 = fma(x0, a, b);
    x1 = fma(x1, a, b);
  }
  for (; i < pc.iterations; ++i) {
    x0 = fma(x0, a, b);
    x1 = fma(x1, a, b);
  }
  results[id] = dot(x0 + x1, vec4(1.0));
}
