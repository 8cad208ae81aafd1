#version 460
// Cluster culling before triangle setup, one thread per cluster: a cluster whose box lies
// wholly outside one plane of the view's frustum is skipped, the others are listed for
// raster_setup (and counted as its indirect dispatch). Exact: a skipped cluster's every
// triangle has all three corners outside that plane, which setup's trivial reject would have
// found (docs/techniques/raster-culling.md). The CPU twin is engine::clusterKept.
#extension GL_GOOGLE_include_directive : require

#include "shared/raster.h"
#include "common/raster_clip.glsl"

layout(local_size_x = RASTER_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Clusters { RasterCluster clusters[]; };
layout(std430, binding = 1) writeonly buffer ClusterList { uint clusterList[]; };
layout(std430, binding = 2) buffer Counters { RasterCounters counters; };
layout(push_constant) uniform Push { RasterSetupPush pc; };

// Setup rejects a triangle whose three corners lie outside one of the frustum's planes,
// x > w, x < -w, y > w, y < -w, z < 0 or z > w, each compared after rounding (raster_clip.glsl).
// Each plane's distance is linear in the position, so over the cluster's box it is smallest at
// a corner: a box whose eight corners are all outside by more than the rounding of both
// transforms holds no triangle that setup keeps. That rounding is below 8 ulps of the sum of
// the terms' magnitudes, sum_j |m_kj| |p_j - origin_j| + |m_k3| for clip coordinate k (five
// roundings, of terms no larger); the margin, 1e-5 of it, is over ten times that bound.
// `precise` and the explicit order make the CPU twin decide every cluster alike.
bool clusterKept(RasterCluster c) {
  if (c.boundsMin.w != 0.0) return true;  // a position that is not finite
  if (any(greaterThan(c.boundsMin.xyz, c.boundsMax.xyz))) return false;  // nothing to draw
  const vec3 o = pc.origin.xyz;
  const vec3 reach = max(abs(c.boundsMin.xyz - o), abs(c.boundsMax.xyz - o));
  precise vec4 scale;  // per clip coordinate: the magnitude of its terms over the box
  for (int k = 0; k < 4; ++k) {
    precise float s = abs(pc.viewProj[0][k]) * reach.x;
    s = s + abs(pc.viewProj[1][k]) * reach.y;
    s = s + abs(pc.viewProj[2][k]) * reach.z;
    scale[k] = s + abs(pc.viewProj[3][k]);
  }
  const float margin = 1e-5;
  precise vec4 limit = margin * vec4(scale.x + scale.w, scale.y + scale.w, scale.z + scale.w, scale.z);
  // Per plane: whether every corner so far lies outside it by more than its limit.
  bvec3 beyondMax = bvec3(true), beyondMin = bvec3(true);  // x, y: > w and < -w; z: > w and < 0
  for (int i = 0; i < 8; ++i) {
    vec3 p = vec3((i & 1) != 0 ? c.boundsMax.x : c.boundsMin.x,
                  (i & 2) != 0 ? c.boundsMax.y : c.boundsMin.y,
                  (i & 4) != 0 ? c.boundsMax.z : c.boundsMin.z);
    vec4 v = rasterClip(pc.viewProj, o, p);
    precise vec3 above = v.xyz - v.w;
    precise vec2 below = -v.xy - v.w;
    beyondMax = bvec3(beyondMax.x && above.x > limit.x, beyondMax.y && above.y > limit.y,
                      beyondMax.z && above.z > limit.z);
    beyondMin = bvec3(beyondMin.x && below.x > limit.x, beyondMin.y && below.y > limit.y,
                      beyondMin.z && -v.z > limit.w);
  }
  return !any(beyondMax) && !any(beyondMin);
}

void main() {
  const uint cluster = gl_GlobalInvocationID.x;
  if (cluster >= (pc.triangleCount + RASTER_GROUP_SIZE - 1u) / RASTER_GROUP_SIZE) return;
  if (pc.cullClusters != 0u && !clusterKept(clusters[cluster])) return;
  clusterList[atomicAdd(counters.clusterCount, 1u)] = cluster;
}
