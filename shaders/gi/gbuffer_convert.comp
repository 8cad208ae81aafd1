#version 460
// A host's G-buffer depth and normal in the encodings it renders (shared/gbuffer_convert.h) turned
// into the module's own, read by every later pass: forward NDC depth (1 = sky) and octahedral
// normals. The host's images are read with texelFetch through sampled views, so a D32 depth image
// works as well as an R32F one. CPU twin: gi/src/reference/gbuffer_convert_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/gbuffer_convert.h"
#include "common/octahedral.glsl"

layout(local_size_x = GBUFFER_CONVERT_GROUP, local_size_y = GBUFFER_CONVERT_GROUP) in;

layout(binding = 0) uniform sampler2D hostDepth;
layout(binding = 1) uniform sampler2D hostNormal;
layout(binding = 2, r32f) uniform writeonly image2D outDepth;
layout(binding = 3, rg16_snorm) uniform writeonly image2D outNormal;
layout(push_constant) uniform Push { GBufferConvertPush pc; };

// Forward NDC depth; anything outside [0, 1), non-finite values included, is the sky's 1.
float forwardDepth(float d) {
  float f = d;
  if (pc.depthEncoding == GBUFFER_DEPTH_REVERSED_NDC) f = 1.0 - d;
  if (pc.depthEncoding == GBUFFER_DEPTH_VIEW_DISTANCE) {
    if (!(d > 0.0) || isinf(d)) return 1.0;  // sky
    float z = -d;                             // the view looks down -z
    vec4 r = pc.depthRow;
    f = (r.x * z + r.y) / (r.z * z + r.w);
  }
  return f >= 0.0 && f < 1.0 ? f : 1.0;
}

vec2 octahedral(vec4 stored) {
  if (pc.normalEncoding == GBUFFER_NORMAL_OCTAHEDRAL) return stored.xy;
  vec3 n = pc.normalEncoding == GBUFFER_NORMAL_WORLD_UNSIGNED ? stored.xyz * 2.0 - 1.0 : stored.xyz;
  float length2 = dot(n, n);
  return length2 > 0.0 ? octEncode(n * inversesqrt(length2)) : vec2(0.0);  // 0: the sky's
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.viewport))) return;
  float depth = forwardDepth(texelFetch(hostDepth, p, 0).r);
  imageStore(outDepth, p, vec4(depth));
  // The sky has no normal in the module's G-buffer (an 8-bit world normal of the sky decodes to a
  // small, non-zero vector that passes reading only the normal would take for a surface).
  vec2 normal = depth < 1.0 ? octahedral(texelFetch(hostNormal, p, 0)) : vec2(0.0);
  imageStore(outNormal, p, vec4(normal, 0.0, 0.0));
}
