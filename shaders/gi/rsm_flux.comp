#version 460
// Reflective shadow map flux pass: the light's G-buffer -> VPL positions (relative to the light)
// and incident/reflected flux per texel (formulas in shaders/shared/rsm_flux.h). The CPU twin is
// gi/src/reference/rsm_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/rsm_flux.h"
#include "common/color.glsl"
#include "common/camera_ray.glsl"

layout(local_size_x = RSM_GROUP_X, local_size_y = RSM_GROUP_Y) in;

layout(binding = 0, r32f) uniform readonly image2D gDepth;
layout(binding = 1, rgba16f) uniform readonly image2D gDiffuse;
layout(binding = 2, rgba16f) uniform readonly image2D gSpecular;
layout(binding = 3, rgba32f) uniform writeonly image2D outPosition;
layout(binding = 4, rgba32f) uniform writeonly image2D outDiffuse;
layout(binding = 5, rgba32f) uniform writeonly image2D outSpecular;
layout(push_constant) uniform Push { RsmFluxPush pc; };

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, pc.size))) return;
  ivec2 coord = ivec2(texel);
  float depth = imageLoad(gDepth, coord).r;
  vec3 incident = vec3(0.0);  // Phi_in, W per colour channel
  vec3 offset = vec3(0.0);
  if (depth < 1.0) {
    // Unprojecting relative to the light keeps the VPL positions accurate: no cancellation
    // against the light's world position (vsgl-math.md section 12, case 6).
    offset = unproject(pc.invViewProjRelative, pixelToNdc(vec2(texel) + 0.5, pc.size), depth);
    if (pc.perspective != 0u) {
      float cosTheta = dot(normalize(offset), pc.axis.xyz);
      float falloff = clamp(cosTheta * pc.spot.x + pc.spot.y, 0.0, 1.0);
      incident = pc.radiance.rgb * (falloff * falloff * pc.spot.z * cosTheta * cosTheta * cosTheta);
    } else {
      incident = pc.radiance.rgb * pc.spot.z;
    }
  }
  float lit = luminance(incident) > 0.0 ? 1.0 : 0.0;
  vec4 diffuseRough = imageLoad(gDiffuse, coord);
  vec3 f0 = imageLoad(gSpecular, coord).rgb;
  imageStore(outPosition, coord, vec4(offset * lit, lit));
  imageStore(outDiffuse, coord, vec4(diffuseRough.rgb * incident, luminance(incident)));
  imageStore(outSpecular, coord, vec4(f0 * incident, diffuseRough.a * lit));
}
