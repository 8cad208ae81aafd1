#version 460
// The box around each cluster of RASTER_GROUP_SIZE consecutive triangles (gpu::RasterCluster),
// one thread per cluster, for geometry that lives only on the GPU (a host's buffers, whose
// vertices may move in place). A thread walks its cluster's triangles itself: a work group's
// reduction through shared memory cost lavapipe more in barriers than the loads. Min and max
// round nothing, so the boxes equal their CPU twin's (engine::clusterBounds) exactly.
#extension GL_GOOGLE_include_directive : require

#include "shared/raster.h"
#include "shared/scene_data.h"

layout(local_size_x = RASTER_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Vertices { SceneVertex vertices[]; };
layout(std430, binding = 1) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 2) writeonly buffer Clusters { RasterCluster clusters[]; };
layout(push_constant) uniform Push { RasterBoundsPush pc; };

void main() {
  const uint cluster = gl_GlobalInvocationID.x;
  const uint first = cluster * RASTER_GROUP_SIZE;
  if (first >= pc.triangleCount) return;
  const uint end = min(first + RASTER_GROUP_SIZE, pc.triangleCount);
  const float inf = uintBitsToFloat(0x7f800000u);
  vec3 lo = vec3(inf), hi = vec3(-inf);  // no triangle: an empty box
  bool finite = true;
  for (uint tri = first; tri < end; ++tri) {
    uvec3 corner = uvec3(indices[3 * tri], indices[3 * tri + 1], indices[3 * tri + 2]);
    // A triangle with a bad index is left out by setup too (raster_setup.comp).
    if (any(greaterThanEqual(corner, uvec3(pc.vertexCount)))) continue;
    for (int i = 0; i < 3; ++i) {
      vec3 p = vertices[corner[i]].positionU.xyz;
      finite = finite && !any(isnan(p)) && !any(isinf(p));
      lo = min(lo, p);
      hi = max(hi, p);
    }
  }
  clusters[cluster] = RasterCluster(vec4(lo, finite ? 0.0 : 1.0), vec4(hi, 0.0));
}
