#version 460
// Direct radiance toward the camera from every punctual light, with 3x3 PCF shadow maps, plus the
// surface's own emission (the G-buffer's emission image). Output: linear HDR radiance
// (W sr^-1 m^-2), background pixels 0.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/direct_light.h"
#include "shared/raster.h"
#include "common/brdf.glsl"
#include "common/camera_ray.glsl"
#include "common/octahedral.glsl"

layout(local_size_x = DIRECT_GROUP_X, local_size_y = DIRECT_GROUP_Y) in;

layout(std140, binding = 0) uniform Lights { GpuLight lights[DIRECT_MAX_LIGHTS]; };
layout(std140, binding = 1) uniform Views { ShadowView shadowViews[DIRECT_MAX_SHADOW_VIEWS]; };
layout(std430, binding = 2) readonly buffer ShadowMaps { uint64_t shadowMaps[]; };
layout(binding = 3, r32f) uniform readonly image2D gDepth;
layout(binding = 4, rg16_snorm) uniform readonly image2D gNormal;
layout(binding = 5, rgba16f) uniform readonly image2D gDiffuse;
layout(binding = 6, rgba16f) uniform readonly image2D gSpecular;
layout(binding = 7, rgba32f) uniform writeonly image2D outRadiance;
layout(binding = 8, rgba16f) uniform readonly image2D gEmission;
layout(push_constant) uniform Push { DirectLightPush pc; };

// Fraction of the 3x3 shadow-map texels around p's projection that see p (1 = lit).
float shadowVisibility(uint viewIndex, vec3 p) {
  vec4 clip = shadowViews[viewIndex].viewProj * vec4(p, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  if (ndc.z < 0.0 || ndc.z > 1.0) return 1.0;  // outside the shadow frustum's depth range
  int size = int(pc.shadowResolution);
  vec2 texel = (ndc.xy * 0.5 + 0.5) * float(size);
  ivec2 centre = ivec2(floor(texel));
  uint base = viewIndex * uint(size * size);
  float lit = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 t = clamp(centre + ivec2(dx, dy), ivec2(0), ivec2(size - 1));
      uint hi = uint(shadowMaps[base + uint(t.y * size + t.x)] >> 32);
      // An empty texel (nothing rendered) never occludes.
      lit += (hi == RASTER_EMPTY_HI || ndc.z <= uintBitsToFloat(hi)) ? 1.0 : 0.0;
    }
  }
  return lit / 9.0;
}

// Index of the cube face (+X, -X, +Y, -Y, +Z, -Z) whose frustum contains direction d.
uint cubeFace(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y >= 0.0 ? 2u : 3u;
  return d.z >= 0.0 ? 4u : 5u;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.viewport))) return;
  ivec2 coord = ivec2(pixel);
  float depth = imageLoad(gDepth, coord).r;
  if (depth >= 1.0) {
    imageStore(outRadiance, coord, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  vec2 ndc = pixelToNdc(vec2(pixel) + 0.5, pc.viewport);
  vec3 p = unproject(pc.invViewProj, ndc, depth);
  vec3 origin, dir;
  cameraRay(pc.invViewProj, ndc, origin, dir);
  vec3 v = -dir;
  vec3 n = octDecode(imageLoad(gNormal, coord).rg);
  vec4 diffuseRough = imageLoad(gDiffuse, coord);
  vec4 specular = imageLoad(gSpecular, coord);  // F0, F90

  vec3 radiance = imageLoad(gEmission, coord).rgb;
  for (uint i = 0u; i < pc.lightCount; ++i) {
    uint type = lights[i].info.x;
    vec3 l;
    vec3 irradiance = lights[i].radiance.rgb;  // at normal incidence, before shadowing
    float distanceToLight = 0.0;
    if (type == LIGHT_DIRECTIONAL) {
      l = -lights[i].direction.xyz;
    } else {
      vec3 toLight = lights[i].position.xyz - p;
      float d2 = max(dot(toLight, toLight), 1e-8);
      distanceToLight = sqrt(d2);
      l = toLight / distanceToLight;
      irradiance /= d2;
      float range = lights[i].radiance.w;
      if (range > 0.0) {  // KHR_lights_punctual's recommended smooth range window
        float r = distanceToLight / range;
        irradiance *= clamp(1.0 - r * r * r * r, 0.0, 1.0);
      }
      if (type == LIGHT_SPOT) {
        float cd = dot(lights[i].direction.xyz, -l);
        float falloff = clamp(cd * lights[i].spot.x + lights[i].spot.y, 0.0, 1.0);
        irradiance *= falloff * falloff;
      }
    }
    vec3 f = brdfCos(n, v, l, diffuseRough.rgb, specular.rgb, specular.a, diffuseRough.a);
    if (all(equal(f, vec3(0.0))) || all(equal(irradiance, vec3(0.0)))) continue;
    float visibility = 1.0;
    uint viewCount = lights[i].info.z;
    if (viewCount > 0u) {
      uint view = lights[i].info.y;
      if (viewCount == 6u) view += cubeFace(p - lights[i].position.xyz);
      float texelWorld = shadowViews[view].texel.x * distanceToLight + shadowViews[view].texel.y;
      vec3 offset = n * (SHADOW_NORMAL_OFFSET_TEXELS * texelWorld);
      visibility = shadowVisibility(view, p + offset);
    }
    radiance += f * irradiance * visibility;
  }
  imageStore(outRadiance, coord, vec4(radiance, 1.0));
}
