#version 460
// Reflective shadow map flux pass: the light's G-buffer -> VPL positions (relative to the light)
// and incident/reflected flux per texel (formulas in shaders/shared/rsm_flux.h). The CPU twin is
// gi/src/reference/rsm_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/rsm_flux.h"
#include "common/color.glsl"
#include "common/camera_ray.glsl"
#include "common/octahedral.glsl"

layout(local_size_x = RSM_GROUP_X, local_size_y = RSM_GROUP_Y) in;

layout(binding = 0, r32f) uniform readonly image2D gDepth;
layout(binding = 1, rgba16f) uniform readonly image2D gDiffuse;
layout(binding = 2, rgba16f) uniform readonly image2D gSpecular;
layout(binding = 3, rgba32f) uniform writeonly image2D outPosition;
layout(binding = 4, rgba32f) uniform writeonly image2D outDiffuse;
layout(binding = 5, rgba32f) uniform writeonly image2D outSpecular;
layout(binding = 6, rg16_snorm) uniform readonly image2D gNormal;
layout(std430, binding = 7) readonly buffer SgGgxAlbedoTable { vec2 kSgGgxAlbedo[]; };
layout(push_constant) uniform Push { RsmFluxPush pc; };

#include "common/sg_lighting.glsl"

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
      if (pc.spot.w > 0.0) {  // the range window of the light's direct light (direct_light.comp)
        float x = length(offset) / pc.spot.w;
        x *= x;
        incident *= clamp(1.0 - x * x, 0.0, 1.0);
      }
    } else {
      incident = pc.radiance.rgb * pc.spot.z;
    }
  }
  float lit = luminance(incident) > 0.0 ? 1.0 : 0.0;
  vec4 diffuseRough = imageLoad(gDiffuse, coord);
  vec4 specular = imageLoad(gSpecular, coord);  // F0, F90
  // The specular lobe's directional albedo for light arriving from the light (brdf.glsl's lobe,
  // the table of common/sg_lighting.glsl): the share of Phi_in it reflects, Fresnel (F0 and F90)
  // and masking included, as the receiver side's glossy term reflects it.
  // Unlit texels (background, outside the cone) keep 0: their offset may be 0.
  vec3 albedo = vec3(0.0);
  if (lit > 0.0) {
    vec3 toLight = pc.perspective != 0u ? -normalize(offset) : -pc.axis.xyz;
    float nl = max(dot(octDecode(imageLoad(gNormal, coord).rg), toLight), kSgGgxMinViewCosine);
    vec2 table = ggxSpecularAlbedo(nl, max(diffuseRough.a * diffuseRough.a, 1e-3));
    albedo = specular.a * table.x + specular.rgb * (table.y - table.x);
  }
  imageStore(outPosition, coord, vec4(offset * lit, lit));
  imageStore(outDiffuse, coord, vec4(diffuseRough.rgb * incident, luminance(incident)));
  imageStore(outSpecular, coord, vec4(albedo * incident, diffuseRough.a * lit));
}
