// The memory-bandwidth micro-kernel (shaders/bench/bandwidth_peak.comp): a copy of a buffer of
// vec4s much larger than any cache, BANDWIDTH_PEAK_PER_THREAD vec4s per thread, reported as
// bytes read plus bytes written per second.
#ifndef SHADERS_SHARED_BANDWIDTH_PEAK_H
#define SHADERS_SHARED_BANDWIDTH_PEAK_H
#include "interop.h"

#define BANDWIDTH_PEAK_GROUP 256
#define BANDWIDTH_PEAK_PER_THREAD 16

SHARED_BEGIN

struct BandwidthPeakPush {
  uint count;  // vec4s to copy
  uint pad0;
  uint pad1;
  uint pad2;
};

SHARED_END

SHARED_ASSERT_SIZE(BandwidthPeakPush, 16);
#endif
