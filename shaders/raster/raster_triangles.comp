#version 460
// Coverage and depth of the compute rasterizer. A work group takes RASTER_GROUP_SIZE set-up
// triangles and spreads the pixels of their boxes evenly over its threads (a prefix sum of box
// areas, then a binary search per pixel), so one big triangle does not stall a lane while the
// others idle. Each covered pixel keeps the nearest (depth, triangle id) pair with a 64-bit
// atomicMin, which makes the result independent of execution order.
// Fill rule: a sample exactly on an edge belongs to the triangle for which that edge is a
// "top-left" edge in our orientation, so shared edges are covered exactly once.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#include "shared/raster.h"

layout(local_size_x = RASTER_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Triangles { RasterTriangle triangles[]; };
layout(std430, binding = 1) readonly buffer Counters { RasterCounters counters; };
layout(std430, binding = 2) buffer Visibility { uint64_t visibility[]; };
layout(push_constant) uniform Push { RasterTrianglesPush pc; };

shared uint sPrefix[RASTER_GROUP_SIZE];  // inclusive prefix sum of pixel-box areas
shared uint sTriangle[RASTER_GROUP_SIZE];

int64_t edge(ivec2 a, ivec2 b, ivec2 p) {
  return int64_t(b.x - a.x) * int64_t(p.y - a.y) - int64_t(b.y - a.y) * int64_t(p.x - a.x);
}

// 0 when samples on the edge a->b are inside, -1 when they are outside (E > 0 required).
// With positive area in y-down screen space, interior is to the right of a->b walked
// clockwise: a top edge runs in +x (d.y == 0, d.x > 0) and a left edge runs upwards (d.y < 0).
int64_t fillBias(ivec2 a, ivec2 b) {
  ivec2 d = b - a;
  bool topLeft = d.y < 0 || (d.y == 0 && d.x > 0);
  return topLeft ? int64_t(0) : int64_t(-1);
}

uvec2 unpackPixel(uint p) { return uvec2(p & 0xFFFFu, p >> 16); }

void main() {
  uint lane = gl_LocalInvocationID.x;
  uint slot = gl_WorkGroupID.x * RASTER_GROUP_SIZE + lane;
  uint count = min(counters.triangleCount, pc.capacity);
  uint area = 0u;
  if (slot < count) {
    uvec2 lo = unpackPixel(triangles[slot].bboxMin), hi = unpackPixel(triangles[slot].bboxMax);
    area = (hi.x - lo.x + 1u) * (hi.y - lo.y + 1u);
  }
  sPrefix[lane] = area;
  sTriangle[lane] = slot;
  barrier();
  // Hillis-Steele inclusive scan; 6 steps for 64 lanes.
  for (uint offset = 1u; offset < RASTER_GROUP_SIZE; offset <<= 1) {
    uint add = lane >= offset ? sPrefix[lane - offset] : 0u;
    barrier();
    sPrefix[lane] += add;
    barrier();
  }
  uint total = sPrefix[RASTER_GROUP_SIZE - 1];

  for (uint k = lane; k < total; k += RASTER_GROUP_SIZE) {
    // First triangle whose inclusive prefix exceeds k.
    uint lo = 0u, hi = RASTER_GROUP_SIZE - 1u;
    while (lo < hi) {
      uint mid = (lo + hi) >> 1;
      if (sPrefix[mid] > k) hi = mid; else lo = mid + 1u;
    }
    uint local = k - (lo > 0u ? sPrefix[lo - 1u] : 0u);
    RasterTriangle t = triangles[sTriangle[lo]];
    uvec2 boxLo = unpackPixel(t.bboxMin), boxHi = unpackPixel(t.bboxMax);
    uint width = boxHi.x - boxLo.x + 1u;
    uvec2 pixel = boxLo + uvec2(local % width, local / width);
    ivec2 sample_ = ivec2(pixel) * int(RASTER_SUBPIXEL_SCALE) + int(RASTER_SUBPIXEL_SCALE) / 2;

    int64_t e0 = edge(t.p1, t.p2, sample_);
    int64_t e1 = edge(t.p2, t.p0, sample_);
    int64_t e2 = edge(t.p0, t.p1, sample_);
    if (e0 + fillBias(t.p1, t.p2) < 0 || e1 + fillBias(t.p2, t.p0) < 0 ||
        e2 + fillBias(t.p0, t.p1) < 0)
      continue;
    precise float sum = float(e0) * t.z0 + float(e1) * t.z1 + float(e2) * t.z2;
    precise float z = sum / float(e0 + e1 + e2);
    if (!(z >= 0.0 && z <= 1.0)) continue;  // beyond the far plane (or NaN)
    uint64_t packed = (uint64_t(floatBitsToUint(z)) << 32) | uint64_t(t.triangleId);
    atomicMin(visibility[pixel.y * pc.viewport.x + pixel.x], packed);
  }
}
