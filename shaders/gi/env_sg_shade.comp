#version 460
// Environment shading with SG lights (docs/techniques/environment.md pass 4): per G-buffer
// pixel, the sum over the distant lights of env_sg_generate.comp of
//   diffuse = albedo * amplitude * D(sharpness, axis . n)        (vsgl-math.md 4.3, [T24])
//   glossy  = amplitude * sgGgxReflection(light, the pixel's GGX receiver)   (section 4.4)
// with common/sg_lighting.glsl. No visibility (the environment is unshadowed); sky pixels 0.
// CPU twin: gi::envSgShade (gi/src/reference/env_sg_reference.cpp).
#extension GL_GOOGLE_include_directive : require

#include "shared/env_sg.h"
#include "common/camera_ray.glsl"
#include "common/finite_material.glsl"
#include "common/octahedral.glsl"
#include "common/sg.glsl"

layout(local_size_x = ENV_SG_SHADE_GROUP_X, local_size_y = ENV_SG_SHADE_GROUP_Y) in;

layout(binding = 0, r32f) uniform readonly image2D gDepth;
layout(binding = 1, rg16_snorm) uniform readonly image2D gNormal;
layout(binding = 2, rgba16f) uniform readonly image2D gDiffuse;
layout(binding = 3, rgba16f) uniform readonly image2D gSpecular;
layout(std430, binding = 4) readonly buffer Lights { EnvSgLight lights[]; };
layout(binding = 5, rgba32f) uniform writeonly image2D outDiffuse;
layout(binding = 6, rgba32f) uniform writeonly image2D outGlossy;
layout(std430, binding = 7) readonly buffer SgGgxAlbedoTable { vec2 kSgGgxAlbedo[]; };
layout(push_constant) uniform Push { EnvSgShadePush pc; };

#include "common/sg_lighting.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.viewport))) return;
  ivec2 coord = ivec2(pixel);
  float depth = imageLoad(gDepth, coord).r;
  if (!(depth < 1.0)) {  // depth 1 = sky: no surface, no light
    imageStore(outDiffuse, coord, vec4(0.0, 0.0, 0.0, 1.0));
    imageStore(outGlossy, coord, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  vec2 ndc = pixelToNdc(vec2(pixel) + 0.5, pc.viewport);
  vec3 origin, direction;
  cameraRay(pc.invViewProjRelative, ndc, origin, direction);
  vec3 view = -direction;
  vec3 normal = octDecode(imageLoad(gNormal, coord).rg);
  // Non-finite material channels read as 0 (albedo, F0, F90) or 1 (roughness).
  vec4 diffuseRoughness = finiteOr(imageLoad(gDiffuse, coord), vec4(0.0, 0.0, 0.0, 1.0));
  vec4 specular = finiteOr(imageLoad(gSpecular, coord), vec4(0.0));
  // The alpha floor of common/brdf.glsl, as vsgl_shade.comp.
  float alpha = max(diffuseRoughness.a * diffuseRoughness.a, 1e-3);
  SgGgxReceiver ggx = sgGgxReceiver(normal, view, alpha, specular.rgb, specular.a);

  vec3 diffuseSum = vec3(0.0);
  vec3 glossySum = vec3(0.0);
  for (uint k = 0u; k < pc.count; ++k) {
    EnvSgLight light = lights[k];
    vec3 amplitude = light.amplitude.rgb;
    if (amplitude == vec3(0.0)) continue;  // a black kernel
    Sg sg = Sg(light.axisSharpness.xyz, light.axisSharpness.w, 0.0);
    diffuseSum += amplitude * sgClampedCosineIntegralOverPi(sg.sharpness, dot(sg.axis, normal));
    glossySum += amplitude * sgGgxReflection(sg, ggx);
  }
  imageStore(outDiffuse, coord, vec4(diffuseRoughness.rgb * diffuseSum, 1.0));
  imageStore(outGlossy, coord, vec4(glossySum, 1.0));
}
