#version 460
// ISM points, step 3 (shaders/shared/ism.h): pool point i of P lies on the triangle where the
// area CDF first exceeds u_i = (i + 1/2) / P of the total area (stratified: every stratum of
// the total area gets exactly one point, so a triangle of area A gets P A / A_total points
// within one), at barycentrics from the R2 low-discrepancy sequence warped to the triangle
// (b0, b1, b2) = (1 - sqrt(r1), sqrt(r1) (1 - r2), sqrt(r1) r2) (uniform in area; Osada et al.
// 2002). Consecutive points of one triangle take consecutive R2 points, which cover it evenly.
// CPU twin: ismPointsReference in gi/src/reference/ism_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"

layout(local_size_x = ISM_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Cdf { float cdf[]; };
layout(std430, binding = 1) writeonly buffer Points { IsmPoint points[]; };
layout(push_constant) uniform Push { IsmPointsPush pc; };

void point(uint i) {
  float total = cdf[pc.triangleCount - 1u];
  if (!(total > 0.0)) {  // no area anywhere: nothing to splat
    points[i] = IsmPoint(ISM_NO_TRIANGLE, 0u);
    return;
  }
  // Exact in fp32: i + 1/2 < 2^23 and P is a power of two.
  float target = (float(i) + 0.5) / float(pc.pointCount) * total;
  // The first triangle whose inclusive CDF exceeds the target (zero-area triangles never do).
  uint lo = 0u, hi = pc.triangleCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1u;
    if (cdf[mid] > target) hi = mid;
    else lo = mid + 1u;
  }
  // R2 in 32-bit fixed point (wrapping products are exact), 24 bits to float exactly.
  uint x1 = 0x80000000u + i * ISM_R2_A1;
  uint x2 = 0x80000000u + i * ISM_R2_A2;
  float r1 = float(x1 >> 8u) * (1.0 / 16777216.0);
  float r2 = float(x2 >> 8u) * (1.0 / 16777216.0);
  float s = sqrt(r1);
  points[i] = IsmPoint(lo, packUnorm2x16(vec2(s * (1.0 - r2), s * r2)));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.pointCount) point(i);
}
