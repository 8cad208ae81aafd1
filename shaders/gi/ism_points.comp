#version 460
// ISM points, step 3 (shaders/shared/ism.h): pool point i of P lies on the triangle where the
// area CDF first exceeds u_i = (i + 1/2) / P of the total area (stratified: every stratum of
// the total area gets exactly one point, so a triangle of area A gets P A / A_total points
// within one), at barycentrics from the R2 low-discrepancy sequence warped to the triangle
// (b0, b1, b2) = (1 - sqrt(r1), sqrt(r1) (1 - r2), sqrt(r1) r2) (uniform in area; Osada et al.
// 2002). Consecutive points of one triangle take consecutive R2 points, which cover it evenly.
// A point where an alpha-tested material is cut (engine/alpha_cutout.h) lies on no surface: it
// becomes ISM_NO_TRIANGLE, so cut-outs let light through the ISMs as they do the RSM.
// CPU twin: ismPointsReference in gi/src/reference/ism_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"
#include "shared/scene_data.h"
#include "common/alpha_cutout.glsl"

layout(local_size_x = ISM_GROUP_SIZE) in;
// 1 when some material is alpha-tested (engine::SceneGpu::alphaCutouts); 0 compiles the test out.
layout(constant_id = 0) const uint kAlphaTest = 0u;

layout(std430, binding = 0) readonly buffer Cdf { float cdf[]; };
layout(std430, binding = 1) writeonly buffer Points { IsmPoint points[]; };
layout(std430, binding = 2) readonly buffer Vertices { SceneVertex vertices[]; };
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 4) readonly buffer TriangleMaterials { uint triangleMaterial[]; };
layout(std430, binding = 5) readonly buffer Materials { SceneMaterial materials[]; };
layout(binding = 6) uniform sampler2DArray baseColorTextures;
layout(push_constant) uniform Push { IsmPointsPush pc; };

// Whether triangle t's surface exists at the packed barycentrics (those ism_positions places
// the point at).
bool pointKept(uint t, uint bary) {
  uint material = triangleMaterial[t];
  if (material >= pc.materialCount) return true;  // a host's bad index: not tested
  float cutoff = materials[material].alphaCutoff;
  if (!(cutoff > 0.0)) return true;
  vec4 rowU = materials[material].baseColorUvU, rowV = materials[material].baseColorUvV;
  vec2 uv[3];
  for (int k = 0; k < 3; ++k) {
    uint v = indices[3u * t + uint(k)];
    uv[k] = cutoutCoordinates(rowU, rowV, vec2(vertices[v].positionU.w, vertices[v].normalV.w));
  }
  vec2 b = unpackUnorm2x16(bary);
  vec2 at = uv[0] + b.x * (uv[1] - uv[0]) + b.y * (uv[2] - uv[0]);
  return cutoutOpaque(baseColorTextures, materials[material].baseColorLayer,
                      materials[material].baseColorFactor.a, cutoff, at);
}

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
  uint bary = packUnorm2x16(vec2(s * (1.0 - r2), s * r2));
  if (kAlphaTest != 0u && !pointKept(lo, bary)) {
    points[i] = IsmPoint(ISM_NO_TRIANGLE, 0u);
    return;
  }
  points[i] = IsmPoint(lo, bary);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.pointCount) point(i);
}
