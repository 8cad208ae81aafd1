#version 460
// ISM build, step 1 (shaders/shared/ism.h): world positions of the pool points that the VSGLs'
// subsets use, from the CURRENT vertex buffer, so the points follow moving geometry. Work group
// row y = subset class c < min(V, s), x = j < M: point o_c + j s. Each position is read by up
// to V / s splat groups, so computing it once here instead of in every splat replaces five
// scattered reads per splat (point, indices, three vertices) by one image load.
// Output (RGBA32F image, ISM_POSITIONS_WIDTH wide): xyz = position, w = 1 (0: no surface).
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"
#include "shared/scene_data.h"

layout(local_size_x = ISM_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Points { IsmPoint points[]; };
layout(std430, binding = 1) readonly buffer Vertices { SceneVertex vertices[]; };
layout(std430, binding = 2) readonly buffer Indices { uint indices[]; };
layout(binding = 3, rgba32f) uniform writeonly image2D positions;
layout(push_constant) uniform Push { IsmPositionsPush pc; };

void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= pc.pointsPerVsgl) return;
  uint i = ISM_SUBSET_OFFSET(gl_WorkGroupID.y, pc.stride) + j * pc.stride;
  ivec2 texel = ivec2(i & (ISM_POSITIONS_WIDTH - 1u), i >> ISM_POSITIONS_SHIFT);
  uint t = points[i].triangle;
  if (t == ISM_NO_TRIANGLE) {
    imageStore(positions, texel, vec4(0.0));
    return;
  }
  vec2 b = unpackUnorm2x16(points[i].bary);
  vec3 a = vertices[indices[3u * t]].positionU.xyz;
  vec3 e1 = vertices[indices[3u * t + 1u]].positionU.xyz - a;
  vec3 e2 = vertices[indices[3u * t + 2u]].positionU.xyz - a;
  imageStore(positions, texel, vec4(a + b.x * e1 + b.y * e2, 1.0));
}
