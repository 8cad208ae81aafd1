#version 460
// The VPL baseline's shading (docs/techniques/vpl-baseline.md): instant radiosity, each record
// of the VSGL buffer a one-texel VPL (VSGL_RULE_POINT) shaded as a point light with the
// receiver's exact BRDF (common/brdf.glsl) and the same ISM visibility as the VSGLs. Per pair,
// with w the unit direction from the receiver x to the VPL at distance d and a its disc's area
// (4 pi times the lobes' variance):
//   L_o = V (I_d(-w) + I_s(-w)) f(w, v) (n . w)^+ / (d^2 + a / pi)
//   I_d = Phi_d (n_y . -w)^+ / pi,  I_s = Phi_s G(-w; xi, lambda') cut(-w) / N(lambda')
// The 1 / d^2 of a point is the on-axis form factor of the disc, bounded where x touches it;
// both glossy lobes are widened by the disc's angular variance s = a / (4 pi d^2) seen from x:
// the receiver's GGX to alpha^2 + s, the VPL's SG to 1 / lambda' = 1 / lambda + s (so a
// near-mirror VPL does not flash on the one receiver it aligns with). cut and N are the planar
// emitter's (common/vsgl_emitter.glsl): no light below the VPL's surface, power kept.
// Shares vsgl_shade.comp's bindings and push constants; reads only VSGL_SHADE_GLOSSY,
// VSGL_SHADE_VISIBILITY, VSGL_SHADE_SKIP_SKY and VSGL_SHADE_DIFFUSE_LOBES.
// The CPU twin is gi/src/reference/vpl_shade_reference.cpp.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "shared/vsgl.h"
#include "shared/vsgl_shade.h"
#include "common/brdf.glsl"
#include "common/camera_ray.glsl"
#include "common/finite_material.glsl"
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
// Read by nothing here, declared for common/sg_lighting.glsl (through vsgl_emitter.glsl).
layout(std430, binding = 8) readonly buffer SgGgxAlbedoTable { vec2 kSgGgxAlbedo[]; };
layout(push_constant) uniform Push { VsglShadePush pc; };
layout(constant_id = 0) const uint kFlags = VSGL_SHADE_GLOSSY | VSGL_SHADE_VISIBILITY;

// The ISM filter (IsmParams::pcf) as a compile-time constant: ism_lookup.glsl's tap loops unroll.
layout(constant_id = 1) const uint kPcf = ISM_PCF_BILINEAR;
#define ISM_LOOKUP_PCF kPcf
#include "common/ism_lookup.glsl"
#include "common/ism_broadcast.glsl"
#include "common/vsgl_emitter.glsl"

// One VPL as the loop sees it: the lane's own record, or lane j's after a broadcast.
struct PointLight {
  vec4 positionArea;   // xyz = position (world), w = the disc's area a (m^2)
  vec4 normal;         // xyz = the surface normal, 0 without diffuse power; w = beta, the
                       // planarity (vsglEmitterPlanarity) that rebuilds the emitter's plane
  vec4 diffusePower;   // rgb = Phi_d (W)
  vec4 axisSharpness;  // the specular lobe's SG
  vec4 specularPower;  // rgb = Phi_s (W); 0 when VSGL_SHADE_DIFFUSE_LOBES leaves it out
};

PointLight pointLight(Vsgl v) {
  PointLight p;
  bool hasNormal = v.diffuse.power.a > 0.0;
  VsglLobe lobe = hasNormal ? v.diffuse : v.specular;
  p.positionArea = vec4(lobe.meanVariance.xyz, 4.0 * kPi * lobe.meanVariance.w);
  // Without a normal beta is 0 (no diffuse weight), so the plane is the SG emitter's either way.
  p.normal = vec4(hasNormal ? v.diffuse.axisSharpness.xyz : vec3(0.0), vsglEmitterPlanarity(v, true));
  p.diffusePower = vec4(v.diffuse.power.rgb, 0.0);
  p.axisSharpness = v.specular.axisSharpness;
  bool specular = (kFlags & VSGL_SHADE_DIFFUSE_LOBES) == 0u;
  p.specularPower = vec4(specular ? v.specular.power.rgb : vec3(0.0), 0.0);
  return p;
}

PointLight broadcastLight(PointLight p, uint lane) {
  return PointLight(subgroupBroadcast(p.positionArea, lane), subgroupBroadcast(p.normal, lane),
                    subgroupBroadcast(p.diffusePower, lane),
                    subgroupBroadcast(p.axisSharpness, lane),
                    subgroupBroadcast(p.specularPower, lane));
}

// The radiant intensity the VPL sends along unit `toward` (from the VPL), its specular SG widened
// by the angular variance `spread`.
vec3 intensity(PointLight p, vec3 toward, float spread) {
  vec3 i = p.diffusePower.rgb * (max(dot(p.normal.xyz, toward), 0.0) / kPi);
  if (all(equal(p.specularPower.rgb, vec3(0.0)))) return i;
  VsglLobe lobe;  // vsglSpecularNormalisation reads its axis and sharpness only
  lobe.axisSharpness = vec4(p.axisSharpness.xyz, p.axisSharpness.w / (1.0 + p.axisSharpness.w * spread));
  float g = exp(lobe.axisSharpness.w * (dot(lobe.axisSharpness.xyz, toward) - 1.0));
  vec4 plane = vsglEmitterPlane(p.normal.xyz, p.normal.w);
  float cut = plane.w + max(dot(plane.xyz, toward), 0.0);
  return i + p.specularPower.rgb * (g * cut / vsglSpecularNormalisation(lobe, plane));
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  // No early return: every invocation takes part in the broadcasts below.
  bool inside = all(lessThan(pixel, pc.viewport));
  ivec2 coord = ivec2(min(pixel, pc.viewport - 1u));
  float depth = imageLoad(gDepth, coord).r;
  bool shaded = inside && depth < 1.0;  // depth 1 = sky: never shaded
  vec2 ndc = pixelToNdc(vec2(coord) + 0.5, pc.viewport);
  vec3 receiver = pc.eye + unproject(pc.invViewProjRelative, ndc, depth);
  vec3 origin, direction;
  cameraRay(pc.invViewProjRelative, ndc, origin, direction);
  vec3 view = -direction;
  vec3 normal = octDecode(imageLoad(gNormal, coord).rg);
  vec4 diffuseRoughness = finiteOr(imageLoad(gDiffuse, coord), vec4(0.0, 0.0, 0.0, 1.0));
  vec4 specular = finiteOr(imageLoad(gSpecular, coord), vec4(0.0));  // F0, F90
  float alpha = max(diffuseRoughness.a * diffuseRoughness.a, kMinAlpha);
  const bool glossy = (kFlags & VSGL_SHADE_GLOSSY) != 0u;
  const bool shadowed = (kFlags & VSGL_SHADE_VISIBILITY) != 0u;
  if ((kFlags & VSGL_SHADE_SKIP_SKY) != 0u && subgroupBallotBitCount(subgroupBallot(shaded)) == 0u) {
    if (inside) {
      imageStore(outDiffuse, ivec2(pixel), vec4(0.0, 0.0, 0.0, 1.0));
      imageStore(outGlossy, ivec2(pixel), vec4(0.0, 0.0, 0.0, 1.0));
    }
    return;
  }
  vec3 diffuseSum = vec3(0.0);  // of I cos_x / (d^2 + a / pi) / pi, times albedo at the end
  vec3 glossySum = vec3(0.0);
  // As in vsgl_shade.comp: each lane loads one VPL of a block, then the block is broadcast.
  uint lanes = subgroupBallotBitCount(subgroupBallot(true));
  for (uint first = 0u; first < pc.vsglCount; first += lanes) {
    uint count = min(lanes, pc.vsglCount - first);
    Vsgl mine = vsgls[first + min(gl_SubgroupInvocationID, count - 1u)];
    PointLight myLight = pointLight(mine);
    IsmFrame myFrame = ismFrame(mine, pc.ism.centreOffset);
    for (uint j = 0u; j < count; ++j) {
      PointLight p = broadcastLight(myLight, j);
      IsmFrame frame = broadcastFrame(myFrame, j);
      if (!shaded) continue;
      vec3 d = p.positionArea.xyz - receiver;
      float d2 = dot(d, d);
      if (!(d2 > 0.0)) continue;
      vec3 w = d * inversesqrt(d2);  // receiver -> VPL
      float cosine = dot(normal, w);
      if (cosine <= 0.0) continue;
      float visibility = shadowed ? ismVisibility(pc.ism, frame, first + j, receiver, normal) : 1.0;
      if (visibility == 0.0) continue;
      float area = p.positionArea.w;
      float spread = area / (4.0 * kPi * d2);
      vec3 arriving = intensity(p, -w, spread) * (visibility / (d2 + area / kPi));
      diffuseSum += arriving * (cosine / kPi);
      if (glossy) {
        float widened = sqrt(sqrt(alpha * alpha + spread));  // back to perceptual roughness
        glossySum += arriving * brdfCos(normal, view, w, vec3(0.0), specular.rgb, specular.a, widened);
      }
    }
  }
  if (inside) {
    imageStore(outDiffuse, ivec2(pixel), vec4(shaded ? diffuseSum * diffuseRoughness.rgb : vec3(0.0), 1.0));
    imageStore(outGlossy, ivec2(pixel), vec4(shaded ? glossySum : vec3(0.0), 1.0));
  }
}
