#version 460
// ISM points, step 1 (shaders/shared/ism.h): the area of every triangle (m^2), written where
// ism_scan.comp turns it into the area CDF. One thread per triangle; the CPU twin is
// ismTriangleCdfReference in gi/src/reference/ism_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"
#include "shared/scene_data.h"

layout(local_size_x = ISM_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Vertices { SceneVertex vertices[]; };
layout(std430, binding = 1) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 2) writeonly buffer Cdf { float cdf[]; };
layout(push_constant) uniform Push { IsmAreaPush pc; };

void area(uint t) {
  uvec3 corner = uvec3(indices[3u * t], indices[3u * t + 1u], indices[3u * t + 2u]);
  if (any(greaterThanEqual(corner, uvec3(pc.vertexCount)))) {  // a host's bad index
    cdf[t] = 0.0;
    return;
  }
  vec3 a = vertices[corner.x].positionU.xyz;
  vec3 b = vertices[corner.y].positionU.xyz;
  vec3 c = vertices[corner.z].positionU.xyz;
  cdf[t] = 0.5 * length(cross(b - a, c - a));
}

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t < pc.triangleCount) area(t);
}
