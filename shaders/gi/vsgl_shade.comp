#version 460
// VSGL shading (shaders/shared/vsgl_shade.h, vsgl-math.md sections 4.1-4.5): per G-buffer pixel,
//   L_o = sum_k V_k sum_{lobe} E e^(l_p) [rho D(lambda_p, xi_p . n) + Lambda_s]
// with the incoming-radiance SG of each lobe (section 4.1), the [T24] SG x clamped-cosine
// integral D for the diffuse term and the SG x GGX integral for the glossy one
// (common/sg_lighting.glsl), and V_k the imperfect-shadow-map test of common/ism_lookup.glsl.
// The CPU twin is gi/src/reference/vsgl_shade_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/vsgl.h"
#include "shared/vsgl_shade.h"
#include "common/camera_ray.glsl"
#include "common/octahedral.glsl"
#include "common/sg.glsl"

layout(local_size_x = VSGL_SHADE_GROUP_X, local_size_y = VSGL_SHADE_GROUP_Y) in;

layout(binding = 0, r32f) uniform readonly image2D gDepth;
layout(binding = 1, rg16_snorm) uniform readonly image2D gNormal;
layout(binding = 2, rgba16f) uniform readonly image2D gDiffuse;
layout(binding = 3, rgba16f) uniform readonly image2D gSpecular;
layout(std430, binding = 4) readonly buffer Vsgls { Vsgl vsgls[]; };
layout(binding = 5, rgba32f) uniform writeonly image2D outDiffuse;
layout(binding = 6, rgba32f) uniform writeonly image2D outGlossy;
layout(binding = 7, r32ui) uniform readonly uimage2D ismAtlas;
layout(std430, binding = 8) readonly buffer SgGgxAlbedoTable { vec2 kSgGgxAlbedo[]; };
layout(push_constant) uniform Push { VsglShadePush pc; };

#include "common/ism_lookup.glsl"
#include "common/sg_lighting.glsl"

// A tile of VSGLs in shared memory: every pixel of the group reads the same lobes, so each is
// fetched and its per-lobe constants computed once per group instead of once per pixel.
const uint kTile = VSGL_SHADE_GROUP_X * VSGL_SHADE_GROUP_Y;  // VSGLs per tile, 2 lobes each
shared vec4 tileMeanVariance[2 * kTile];
shared vec4 tileAxisSharpness[2 * kTile];
// rgb = power / its largest component (the lobe's colour), a = log(largest component /
// (2 pi S(sharpness))), the scale of E kept as a logarithm so that it meets the SG product's
// tiny amplitude inside one exp() (section 4.2); -inf for a lobe without power.
shared vec4 tileColourLogScale[2 * kTile];
// Each VSGL's ISM frame (section 8): centre with w = 1 when the VSGL has power, then its basis.
shared vec4 tileIsmCentre[kTile];
shared vec3 tileIsmTangent[kTile];
shared vec3 tileIsmBitangent[kTile];
shared vec3 tileIsmAxis[kTile];

void loadLobe(uint slot, VsglLobe lobe) {
  tileMeanVariance[slot] = lobe.meanVariance;
  tileAxisSharpness[slot] = lobe.axisSharpness;
  float largest = max(lobe.power.r, max(lobe.power.g, lobe.power.b));
  tileColourLogScale[slot] =
      largest > 0.0 ? vec4(lobe.power.rgb / largest, log(largest) - log(2.0 * kSgPi) -
                                                         log(sgIntegral(lobe.axisSharpness.w)))
                    : vec4(0.0, 0.0, 0.0, -1.0 / 0.0);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  // No early return: every invocation takes part in the tile barriers.
  bool inside = all(lessThan(pixel, pc.viewport));
  ivec2 coord = ivec2(min(pixel, pc.viewport - 1u));
  float depth = imageLoad(gDepth, coord).r;
  bool shaded = inside && depth < 1.0;  // depth 1 = sky: never shaded

  vec2 ndc = pixelToNdc(vec2(coord) + 0.5, pc.viewport);
  vec3 receiver = unproject(pc.invViewProj, ndc, depth);
  vec3 origin, direction;
  cameraRay(pc.invViewProj, ndc, origin, direction);
  vec3 view = -direction;
  vec3 normal = octDecode(imageLoad(gNormal, coord).rg);
  vec4 diffuseRoughness = imageLoad(gDiffuse, coord);
  vec3 f0 = imageLoad(gSpecular, coord).rgb;
  // The same alpha floor as the direct light's BRDF (common/brdf.glsl).
  float alpha = max(diffuseRoughness.a * diffuseRoughness.a, 1e-3);
  bool glossy = (pc.flags & VSGL_SHADE_GLOSSY) != 0u;
  bool shadowed = (pc.flags & VSGL_SHADE_VISIBILITY) != 0u;

  vec3 diffuseSum = vec3(0.0);  // sum of E e^(l_p) D, times albedo at the end
  vec3 glossySum = vec3(0.0);
  uint local = gl_LocalInvocationIndex;
  for (uint first = 0u; first < pc.vsglCount; first += kTile) {
    uint count = min(kTile, pc.vsglCount - first);
    if (local < count) {
      Vsgl v = vsgls[first + local];
      loadLobe(2u * local, v.diffuse);
      loadLobe(2u * local + 1u, v.specular);
      IsmFrame f = ismFrame(v, pc.ism.centreOffset);
      tileIsmCentre[local] = vec4(f.centre, f.lit ? 1.0 : 0.0);
      tileIsmTangent[local] = f.tangent;
      tileIsmBitangent[local] = f.bitangent;
      tileIsmAxis[local] = f.axis;
    }
    barrier();
    if (shaded) {
      for (uint k = 0u; k < count; ++k) {
        // One test per VSGL: both lobes share its map.
        float visibility = 1.0;
        if (shadowed) {
          IsmFrame f;
          f.centre = tileIsmCentre[k].xyz;
          f.lit = tileIsmCentre[k].w > 0.0;
          f.tangent = tileIsmTangent[k];
          f.bitangent = tileIsmBitangent[k];
          f.axis = tileIsmAxis[k];
          visibility = ismVisibility(pc.ism, f, first + k, receiver, normal);
        }
        if (visibility == 0.0) continue;
        for (uint slot = 2u * k; slot < 2u * k + 2u; ++slot) {
          vec4 colourLogScale = tileColourLogScale[slot];
          vec4 meanVariance = tileMeanVariance[slot];
          vec4 axisSharpness = tileAxisSharpness[slot];
          Sg radiance = vsglIncomingRadiance(meanVariance.xyz, meanVariance.w, axisSharpness.xyz,
                                             axisSharpness.w, colourLogScale.a, receiver);
          float amplitude = exp(min(radiance.logAmplitude, VSGL_SHADE_MAX_LOG_RADIANCE));
          if (amplitude == 0.0) continue;  // no power, or an overlap below fp32 range
          vec3 e = (visibility * amplitude) * colourLogScale.rgb;
          diffuseSum += e * sgClampedCosineIntegralOverPi(radiance.sharpness,
                                                          dot(radiance.axis, normal));
          if (glossy) glossySum += e * sgGgxReflection(radiance, normal, view, alpha, f0);
        }
      }
    }
    barrier();
  }
  if (inside) {
    imageStore(outDiffuse, coord, vec4(shaded ? diffuseSum * diffuseRoughness.rgb : vec3(0.0), 1.0));
    imageStore(outGlossy, coord, vec4(shaded ? glossySum : vec3(0.0), 1.0));
  }
}
