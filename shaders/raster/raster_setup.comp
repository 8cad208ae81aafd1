#version 460
// Triangle setup of the compute rasterizer, one work group per cluster that raster_cull kept and
// one thread per triangle in it: transform to clip space, reject triangles outside the frustum,
// snap to fixed point and append the triangles with a non-empty pixel box. The few that cross
// the near plane or the guard band are listed instead and clipped by a second, indirect
// dispatch of this shader (kClipPass): lavapipe (llvmpipe) pays for the clipper's polygon
// arrays in every invocation of a pipeline that declares them, reached or not, which made
// setup five times slower (docs/performance.md).
// The CPU twin is engine/src/raster_reference.cpp; both must round identically, hence
// `precise` (no FMA contraction) and the explicit evaluation order of every product.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/raster.h"
#include "shared/scene_data.h"
#include "common/raster_clip.glsl"

layout(local_size_x = RASTER_GROUP_SIZE) in;
// 0: the triangles of the kept clusters (setup); 1: those setup listed for clipping.
layout(constant_id = 0) const uint kClipPass = 0;

layout(std430, binding = 0) readonly buffer Vertices { SceneVertex vertices[]; };
layout(std430, binding = 1) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 2) writeonly buffer Triangles { RasterTriangle triangles[]; };
layout(std430, binding = 3) buffer Counters { RasterCounters counters; };
// Pixel-box area of each group of RASTER_GROUP_SIZE list entries (zeroed before the pass): the
// coverage pass's work groups per group of triangles (RASTER_CHUNK_PIXELS).
layout(std430, binding = 4) buffer GroupAreas { uint groupAreas[]; };
// The triangles that need clipping (RasterCounters::clipCount of them).
layout(std430, binding = 5) buffer ClipList { uint clipList[]; };
// The clusters raster_cull kept (RasterCounters::clusterCount of them): this pass's work groups.
layout(std430, binding = 6) readonly buffer ClusterList { uint clusterList[]; };
layout(push_constant) uniform Push { RasterSetupPush pc; };

vec4 toClip(vec3 world) { return rasterClip(pc.viewProj, pc.origin.xyz, world); }

// Signed distance to clip plane k (inside >= 0): near z >= 0, then |x|, |y| <= G w.
float planeDistance(vec4 v, int k) {
  precise float g = RASTER_GUARD_BAND * v.w;
  if (k == 0) return v.z;
  if (k == 1) return g - v.x;
  if (k == 2) return g + v.x;
  if (k == 3) return g - v.y;
  return g + v.y;
}

// The intersection is always interpolated from the inside vertex towards the outside one, so
// the two triangles sharing an edge compute bit-identical clipped vertices (no cracks).
vec4 intersectEdge(vec4 inside, float dIn, vec4 outside, float dOut) {
  precise float t = dIn / (dIn - dOut);
  precise vec4 r = inside + (outside - inside) * t;
  return r;
}

ivec2 toFixed(vec4 v) {
  precise vec2 ndc = v.xy / v.w;
  precise vec2 screen = (ndc * 0.5 + 0.5) * vec2(pc.viewport);
  return ivec2(floor(screen * RASTER_SUBPIXEL_SCALE + 0.5));
}

int64_t edge(ivec2 a, ivec2 b, ivec2 p) {
  return int64_t(b.x - a.x) * int64_t(p.y - a.y) - int64_t(b.y - a.y) * int64_t(p.x - a.x);
}

void emit(vec4 c0, vec4 c1, vec4 c2, uint triangleId) {
  ivec2 p0 = toFixed(c0), p1 = toFixed(c1), p2 = toFixed(c2);
  precise float z0 = c0.z / c0.w;
  precise float z1 = c1.z / c1.w;
  precise float z2 = c2.z / c2.w;
  int64_t area = edge(p0, p1, p2);
  if (area == 0) return;  // degenerate after snapping: covers no sample
  if (area < 0) {         // no back-face culling: flip to a positive orientation
    ivec2 tp = p1; p1 = p2; p2 = tp;
    float tz = z1; z1 = z2; z2 = tz;
  }
  // Pixel box of the sample points (pixel centres at x + 0.5) inside the vertex box.
  const int half_ = int(RASTER_SUBPIXEL_SCALE) / 2;
  ivec2 lo = min(min(p0, p1), p2), hi = max(max(p0, p1), p2);
  ivec2 pixLo = (lo - half_ + int(RASTER_SUBPIXEL_SCALE) - 1) >> RASTER_SUBPIXEL_BITS;
  ivec2 pixHi = (hi - half_) >> RASTER_SUBPIXEL_BITS;
  pixLo = max(pixLo, ivec2(0));
  pixHi = min(pixHi, ivec2(pc.viewport) - 1);
  if (pixLo.x > pixHi.x || pixLo.y > pixHi.y) return;

  uint slot = atomicAdd(counters.triangleCount, 1u);
  if (slot >= pc.capacity) {
    atomicAdd(counters.dropped, 1u);
    return;
  }
  atomicMax(counters.groupsX, slot / RASTER_GROUP_SIZE + 1u);
  uint boxArea = uint(pixHi.x - pixLo.x + 1) * uint(pixHi.y - pixLo.y + 1);
  uint groupArea = atomicAdd(groupAreas[slot / RASTER_GROUP_SIZE], boxArea) + boxArea;
  atomicMax(counters.groupsY, (groupArea + (RASTER_CHUNK_PIXELS - 1u)) / RASTER_CHUNK_PIXELS);
  RasterTriangle t;
  t.p0 = p0; t.p1 = p1; t.p2 = p2;
  t.bboxMin = uint(pixLo.x) | (uint(pixLo.y) << 16);
  t.bboxMax = uint(pixHi.x) | (uint(pixHi.y) << 16);
  t.z0 = z0; t.z1 = z1; t.z2 = z2;
  t.triangleId = triangleId;
  triangles[slot] = t;
}

// Sutherland-Hodgman against the near plane and the four guard-band planes, then the fan.
void clipAndEmit(vec4 v[3], uint tri) {
  vec4 poly[RASTER_MAX_CLIP_VERTICES + 1];
  vec4 next[RASTER_MAX_CLIP_VERTICES + 1];
  int n = 3;
  poly[0] = v[0]; poly[1] = v[1]; poly[2] = v[2];
  for (int k = 0; k < 5 && n > 0; ++k) {
    int m = 0;
    for (int i = 0; i < n; ++i) {
      vec4 a = poly[i], b = poly[(i + 1) % n];
      float da = planeDistance(a, k), db = planeDistance(b, k);
      if (da >= 0.0) next[m++] = a;
      if ((da >= 0.0) != (db >= 0.0))
        next[m++] = da >= 0.0 ? intersectEdge(a, da, b, db) : intersectEdge(b, db, a, da);
    }
    n = m;
    for (int i = 0; i < n; ++i) poly[i] = next[i];
  }
  for (int i = 1; i + 1 < n; ++i) emit(poly[0], poly[i], poly[i + 1], tri);
}

// The triangle's clip-space corners; false for a host's bad index (the triangle is left out).
bool loadTriangle(uint tri, out vec4 v[3]) {
  uvec3 corner = uvec3(indices[3 * tri], indices[3 * tri + 1], indices[3 * tri + 2]);
  if (any(greaterThanEqual(corner, uvec3(pc.vertexCount)))) return false;
  for (int i = 0; i < 3; ++i) v[i] = toClip(vertices[corner[i]].positionU.xyz);
  return true;
}

void main() {
  vec4 v[3];
  if (kClipPass != 0u) {
    uint entry = gl_GlobalInvocationID.x;
    if (entry >= counters.clipCount) return;
    uint tri = clipList[entry];
    if (loadTriangle(tri, v)) clipAndEmit(v, tri);
    return;
  }
  uint tri = clusterList[gl_WorkGroupID.x] * RASTER_GROUP_SIZE + gl_LocalInvocationID.x;
  if (tri >= pc.triangleCount || !loadTriangle(tri, v)) return;

  // Trivial reject against the real frustum (not the guard band): all outside one plane.
  for (int axis = 0; axis < 2; ++axis) {
    if (v[0][axis] > v[0].w && v[1][axis] > v[1].w && v[2][axis] > v[2].w) return;
    if (v[0][axis] < -v[0].w && v[1][axis] < -v[1].w && v[2][axis] < -v[2].w) return;
  }
  if (v[0].z < 0.0 && v[1].z < 0.0 && v[2].z < 0.0) return;
  if (v[0].z > v[0].w && v[1].z > v[1].w && v[2].z > v[2].w) return;

  bool inside = true;
  for (int k = 0; k < 5; ++k)
    for (int i = 0; i < 3; ++i) inside = inside && planeDistance(v[i], k) >= 0.0;
  if (inside) {
    emit(v[0], v[1], v[2], tri);
    return;
  }
  uint entry = atomicAdd(counters.clipCount, 1u);  // clipList holds every triangle: no overflow
  atomicMax(counters.clipGroupsX, entry / RASTER_GROUP_SIZE + 1u);
  clipList[entry] = tri;
}
