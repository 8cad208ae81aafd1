#version 460
// The "one VSGL's visibility" debug view (shaders/shared/ism.h): for every pixel of a camera
// G-buffer, ismVisibility (common/ism_lookup.glsl) of VSGL pc.vsglIndex at the pixel's world
// position and normal; background pixels get 1. Output R32_SFLOAT in [0, 1]. CPU twin:
// ismVisibilityReference; ground truth: ismRayCastVisible.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"
#include "shared/vsgl.h"
#include "common/camera_ray.glsl"
#include "common/octahedral.glsl"

layout(local_size_x = ISM_IMAGE_GROUP, local_size_y = ISM_IMAGE_GROUP) in;

layout(binding = 0, r32f) uniform readonly image2D gDepth;
layout(binding = 1, rg16_snorm) uniform readonly image2D gNormal;
layout(std430, binding = 2) readonly buffer Vsgls { Vsgl vsgls[]; };
layout(binding = 3, r32ui) uniform readonly uimage2D ismAtlas;  // level 0 of Ism::atlas()
layout(binding = 4, r32f) uniform writeonly image2D outVisibility;
layout(push_constant) uniform Push { IsmVisibilityPush pc; };

#include "common/ism_lookup.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.viewport))) return;
  ivec2 coord = ivec2(pixel);
  float depth = imageLoad(gDepth, coord).r;
  float visibility = 1.0;
  if (depth < 1.0) {
    vec3 p = unproject(pc.invViewProj, pixelToNdc(vec2(pixel) + 0.5, pc.viewport), depth);
    vec3 n = octDecode(imageLoad(gNormal, coord).rg);
    visibility = ismVisibility(pc.params, vsgls[pc.vsglIndex], pc.vsglIndex, p, n);
  }
  imageStore(outVisibility, coord, vec4(visibility));
}
