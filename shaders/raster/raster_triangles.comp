#version 460
// Coverage and depth of the compute rasterizer. Work group (x, y) takes set-up triangles
// x RASTER_GROUP_SIZE onwards and spreads pixels y RASTER_CHUNK_PIXELS onwards of their boxes
// (at most that many) evenly over its threads (a prefix sum of box areas, then a binary search
// per pixel), so one big triangle does not stall a lane while the others idle, nor a work group
// while the others idle, and no thread loops past lavapipe's limit (shared/raster.h). Each covered pixel keeps the nearest (depth, triangle id) pair with a 64-bit
// atomicMin, which makes the result independent of execution order.
// Fill rule: a sample exactly on an edge belongs to the triangle for which that edge is a
// "top-left" edge in our orientation, so shared edges are covered exactly once.
// Alpha-tested materials (glTF MASK, engine/alpha_cutout.h) leave a pixel uncovered where the
// cut-out test fails, in the variant that kAlphaTest compiles in.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#include "shared/raster.h"
#include "shared/scene_data.h"
#include "common/alpha_cutout.glsl"
#include "common/raster_clip.glsl"

layout(local_size_x = RASTER_GROUP_SIZE) in;
// 1 when some material is alpha-tested (engine::SceneGpu::alphaCutouts); 0 compiles the test out.
layout(constant_id = 0) const uint kAlphaTest = 0u;

layout(std430, binding = 0) readonly buffer Triangles { RasterTriangle triangles[]; };
layout(std430, binding = 1) readonly buffer Counters { RasterCounters counters; };
layout(std430, binding = 2) buffer Visibility { uint64_t visibility[]; };
layout(std430, binding = 3) readonly buffer Vertices { SceneVertex vertices[]; };
layout(std430, binding = 4) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 5) readonly buffer TriangleMaterials { uint triangleMaterial[]; };
layout(std430, binding = 6) readonly buffer Materials { SceneMaterial materials[]; };
layout(binding = 7) uniform sampler2DArray baseColorTextures;
layout(std430, binding = 8) readonly buffer GroupAreas { uint groupAreas[]; };
layout(push_constant) uniform Push { RasterTrianglesPush pc; };

shared uint sPrefix[RASTER_GROUP_SIZE];  // inclusive prefix sum of pixel-box areas
// The group's triangles, staged once: the pixel loop then reads shared memory instead of
// gathering 48-byte structs from the storage buffer for every pixel.
shared ivec4 sP01[RASTER_GROUP_SIZE];    // p0.xy, p1.xy (fixed point)
shared ivec4 sP2Box[RASTER_GROUP_SIZE];  // p2.xy, box origin x, box width
shared vec4 sDepth[RASTER_GROUP_SIZE];   // z0, z1, z2, 1 / box width
shared uvec2 sIdBoxY[RASTER_GROUP_SIZE]; // triangle id, box origin y
// Alpha-tested triangles: the edge functions of the SOURCE triangle in 2-D homogeneous screen
// coordinates (Olano and Greer 1997), so a pixel p has perspective-correct barycentrics
// lambda_i = dot(sEdge_i, (p, 1)) / sum_j dot(sEdge_j, (p, 1)), right for the pieces the setup
// clipped too; the base colour coordinates of its corners; (layer, alpha factor, cutoff,
// unused), cutoff 0 for a triangle that is not tested.
shared vec3 sEdge0[RASTER_GROUP_SIZE];
shared vec3 sEdge1[RASTER_GROUP_SIZE];
shared vec3 sEdge2[RASTER_GROUP_SIZE];
shared vec4 sUv01[RASTER_GROUP_SIZE];
shared vec2 sUv2[RASTER_GROUP_SIZE];
shared vec4 sCutout[RASTER_GROUP_SIZE];

// Below this fixed-point extent (64 pixels) |b - a| and |p - a| stay under 2^15, so both edge
// products fit in 31 bits and int32 arithmetic is exact; larger triangles use int64.
const int kSmallExtent = 1 << 14;

int64_t edge64(ivec2 a, ivec2 b, ivec2 p) {
  return int64_t(b.x - a.x) * int64_t(p.y - a.y) - int64_t(b.y - a.y) * int64_t(p.x - a.x);
}

int edge32(ivec2 a, ivec2 b, ivec2 p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// 0 when samples on the edge a->b are inside, -1 when they are outside (E > 0 required).
// With positive area in y-down screen space, interior is to the right of a->b walked
// clockwise: a top edge runs in +x (d.y == 0, d.x > 0) and a left edge runs upwards (d.y < 0).
int fillBias(ivec2 a, ivec2 b) {
  ivec2 d = b - a;
  bool topLeft = d.y < 0 || (d.y == 0 && d.x > 0);
  return topLeft ? 0 : -1;
}

uvec2 unpackPixel(uint p) { return uvec2(p & 0xFFFFu, p >> 16); }

vec3 crossExact(vec3 a, vec3 b) {
  precise vec3 r = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return r;
}

// Stages the alpha test of source triangle `tri` for this lane (raster_reference.cpp, twin).
void stageCutout(uint lane, uint tri) {
  sCutout[lane] = vec4(0.0);
  uint material = triangleMaterial[tri];
  if (material >= pc.materialCount) return;  // a host's bad index: not tested
  float cutoff = materials[material].alphaCutoff;
  if (!(cutoff > 0.0)) return;
  vec4 rowU = materials[material].baseColorUvU, rowV = materials[material].baseColorUvV;
  vec3 h[3];
  vec2 uv[3];
  for (int i = 0; i < 3; ++i) {
    uint v = indices[3u * tri + uint(i)];
    vec4 positionU = vertices[v].positionU;
    vec4 c = rasterClip(pc.viewProj, pc.origin.xyz, positionU.xyz);
    // Screen position x w: ((x / w) 0.5 + 0.5) viewport = (x + w) (viewport / 2) / w.
    precise float sx = (c.x + c.w) * (0.5 * float(pc.viewport.x));
    precise float sy = (c.y + c.w) * (0.5 * float(pc.viewport.y));
    h[i] = vec3(sx, sy, c.w);
    uv[i] = cutoutCoordinates(rowU, rowV, vec2(positionU.w, vertices[v].normalV.w));
  }
  sEdge0[lane] = crossExact(h[1], h[2]);
  sEdge1[lane] = crossExact(h[2], h[0]);
  sEdge2[lane] = crossExact(h[0], h[1]);
  sUv01[lane] = vec4(uv[0], uv[1]);
  sUv2[lane] = uv[2];
  sCutout[lane] = vec4(float(materials[material].baseColorLayer),
                       materials[material].baseColorFactor.a, cutoff, 0.0);
}

// Whether staged triangle k's surface exists at the sample s (fixed point).
bool cutoutKeeps(uint k, ivec2 s) {
  precise vec2 p = vec2(s) * (1.0 / RASTER_SUBPIXEL_SCALE);
  precise float l0 = (sEdge0[k].x * p.x + sEdge0[k].y * p.y) + sEdge0[k].z;
  precise float l1 = (sEdge1[k].x * p.x + sEdge1[k].y * p.y) + sEdge1[k].z;
  precise float l2 = (sEdge2[k].x * p.x + sEdge2[k].y * p.y) + sEdge2[k].z;
  precise float sum = (l0 + l1) + l2;
  precise vec2 uv = ((sUv01[k].xy * l0 + sUv01[k].zw * l1) + sUv2[k] * l2) / sum;
  vec4 c = sCutout[k];
  return cutoutOpaque(baseColorTextures, int(c.x), c.y, c.z, uv);
}

void main() {
  // Groups of small triangles need fewer chunks than the largest group (uniform exit).
  uint chunkBegin = gl_WorkGroupID.y * RASTER_CHUNK_PIXELS;
  if (chunkBegin >= groupAreas[gl_WorkGroupID.x]) return;
  uint lane = gl_LocalInvocationID.x;
  uint slot = gl_WorkGroupID.x * RASTER_GROUP_SIZE + lane;
  uint count = min(counters.triangleCount, pc.capacity);
  uint area = 0u;
  if (slot < count) {
    RasterTriangle t = triangles[slot];
    uvec2 lo = unpackPixel(t.bboxMin), hi = unpackPixel(t.bboxMax);
    uint width = hi.x - lo.x + 1u;
    area = width * (hi.y - lo.y + 1u);
    sP01[lane] = ivec4(t.p0, t.p1);
    sP2Box[lane] = ivec4(t.p2, int(lo.x), int(width));
    sDepth[lane] = vec4(t.z0, t.z1, t.z2, 1.0 / float(width));
    sIdBoxY[lane] = uvec2(t.triangleId, lo.y);
    if (kAlphaTest != 0u) stageCutout(lane, t.triangleId);
  }
  sPrefix[lane] = area;
  barrier();
  // Hillis-Steele inclusive scan; 6 steps for 64 lanes.
  for (uint offset = 1u; offset < RASTER_GROUP_SIZE; offset <<= 1) {
    uint add = lane >= offset ? sPrefix[lane - offset] : 0u;
    barrier();
    sPrefix[lane] += add;
    barrier();
  }
  uint chunkEnd = min(sPrefix[RASTER_GROUP_SIZE - 1], chunkBegin + RASTER_CHUNK_PIXELS);

  for (uint k = chunkBegin + lane; k < chunkEnd; k += RASTER_GROUP_SIZE) {
    // First triangle whose inclusive prefix exceeds k.
    uint lo = 0u, hi = RASTER_GROUP_SIZE - 1u;
    while (lo < hi) {
      uint mid = (lo + hi) >> 1;
      if (sPrefix[mid] > k) hi = mid; else lo = mid + 1u;
    }
    int local = int(k - (lo > 0u ? sPrefix[lo - 1u] : 0u));
    ivec4 p01 = sP01[lo], p2Box = sP2Box[lo];
    vec4 depth = sDepth[lo];
    // Row and column of `local` in the box without an integer division (scalar on CPUs):
    // the float estimate is off by at most one row, which the correction fixes.
    int width = p2Box.w;
    int row = int((float(local) + 0.5) * depth.w);
    int column = local - row * width;
    if (column < 0) { row -= 1; column += width; }
    else if (column >= width) { row += 1; column -= width; }
    uvec2 pixel = uvec2(p2Box.z + column, sIdBoxY[lo].y + uint(row));
    ivec2 s = ivec2(pixel) * int(RASTER_SUBPIXEL_SCALE) + int(RASTER_SUBPIXEL_SCALE) / 2;

    ivec2 p0 = p01.xy, p1 = p01.zw, p2 = p2Box.xy;
    ivec2 extent = max(max(p0, p1), p2) - min(min(p0, p1), p2);
    int64_t e0, e1, e2;
    if (max(extent.x, extent.y) < kSmallExtent) {
      e0 = edge32(p1, p2, s);
      e1 = edge32(p2, p0, s);
      e2 = edge32(p0, p1, s);
    } else {
      e0 = edge64(p1, p2, s);
      e1 = edge64(p2, p0, s);
      e2 = edge64(p0, p1, s);
    }
    if (e0 + fillBias(p1, p2) < 0 || e1 + fillBias(p2, p0) < 0 || e2 + fillBias(p0, p1) < 0)
      continue;
    precise float sum = float(e0) * depth.x + float(e1) * depth.y + float(e2) * depth.z;
    precise float z = sum / float(e0 + e1 + e2);
    if (!(z >= 0.0 && z <= 1.0)) continue;  // beyond the far plane (or NaN)
    if (kAlphaTest != 0u && sCutout[lo].z > 0.0 && !cutoutKeeps(lo, s)) continue;
    uint64_t packed = (uint64_t(floatBitsToUint(z)) << 32) | uint64_t(sIdBoxY[lo].x);
    atomicMin(visibility[pixel.y * pc.viewport.x + pixel.x], packed);
  }
}
