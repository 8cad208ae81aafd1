#version 460
// Memory bandwidth (shaders/shared/bandwidth_peak.h): thread i copies vec4s i, i + T, i + 2T, ...
// (T threads in all, BANDWIDTH_PEAK_PER_THREAD each): neighbouring threads touch neighbouring
// addresses on every step, and a thread's fixed cost is spread over several copies. A plain
// copy is what a bandwidth-bound pass does (read once, write once), and its result can be
// checked: the CPU twin is the identity (engine/src/machine_peak.cpp). On lavapipe (2 cores)
// it reads 1.5-6.7 GB/s from run to run, with 4, 16 or 64 vec4s per thread alike.
#extension GL_GOOGLE_include_directive : require

#include "shared/bandwidth_peak.h"

layout(local_size_x = BANDWIDTH_PEAK_GROUP) in;
layout(std430, binding = 0) readonly buffer Source { vec4 source[]; };
layout(std430, binding = 1) writeonly buffer Destination { vec4 destination[]; };
layout(push_constant) uniform Push { BandwidthPeakPush pc; };

void main() {
  uint threads = gl_NumWorkGroups.x * BANDWIDTH_PEAK_GROUP;
  for (uint k = 0u; k < BANDWIDTH_PEAK_PER_THREAD; ++k) {
    uint i = gl_GlobalInvocationID.x + k * threads;
    if (i < pc.count) destination[i] = source[i];
  }
}
