#version 460
// VSGL shading (shaders/shared/vsgl_shade.h, vsgl-math.md sections 4.1-4.5): per G-buffer pixel,
//   L_o = sum_k V_k sum_{lobe} E e^(l_p) [rho D(lambda_p, xi_p . n) + Lambda_s]
// with the incoming-radiance SG of each lobe (section 4.1; flat clusters as planar emitters,
// common/vsgl_emitter.glsl), the [T24] SG x clamped-cosine
// integral D for the diffuse term and the SG x GGX integral for the glossy one
// (common/sg_lighting.glsl), and V_k the imperfect-shadow-map test of common/ism_lookup.glsl.
// The CPU twin is gi/src/reference/vsgl_shade_reference.cpp.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_vote : require

#include "shared/adaptive_shading.h"
#include "shared/vsgl.h"
#include "shared/vsgl_shade.h"
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
layout(std430, binding = 8) readonly buffer SgGgxAlbedoTable { vec2 kSgGgxAlbedo[]; };
// VSGL_SHADE_QUEUE: the texels to shade (bound, unread, otherwise).
layout(std430, binding = 9) readonly buffer Queue {
  AdaptiveQueueHeader head;
  uint entries[];
};
// VSGL_SHADE_CULL: subgroup x VSGL tests and skips per level (VsglShadeStats).
layout(std430, binding = 10) buffer Stats { VsglShadeStats stats; };
layout(push_constant) uniform Push { VsglShadePush pc; };
layout(constant_id = 0) const uint kFlags = VSGL_SHADE_GLOSSY | VSGL_SHADE_VISIBILITY;

// The ISM filter (IsmParams::pcf) as a compile-time constant: ism_lookup.glsl's tap loops unroll.
layout(constant_id = 1) const uint kPcf = ISM_PCF_BILINEAR;
#define ISM_LOOKUP_PCF kPcf
#include "common/ism_lookup.glsl"
#include "common/ism_broadcast.glsl"
#include "common/sg_lighting.glsl"
#include "common/vsgl_bound.glsl"
#include "common/vsgl_emitter.glsl"

// Per-lobe constants, computed once by the lane that loads the VSGL. rgb = power / its largest
// component (the lobe's colour), a = log(largest component / (2 pi)) - logNormalisation, the
// scale of E kept as a logarithm so that it meets the SG product's tiny amplitude inside one
// exp() (section 4.2); -inf for a lobe without power.
vec4 colourLogScale(VsglLobe lobe, float logNormalisation) {
  float largest = max(lobe.power.r, max(lobe.power.g, lobe.power.b));
  return largest > 0.0
             ? vec4(lobe.power.rgb / largest, log(largest) - log(2.0 * kSgPi) - logNormalisation)
             : vec4(0.0, 0.0, 0.0, -1.0 / 0.0);
}

// One lobe as the loop sees it: the lane's own VSGL, or lane j's after a broadcast.
struct ShadeLobe {
  vec4 meanVariance;
  vec4 axisSharpness;
  vec4 colourLogScale;
};

// The diffuse lobe's normalisation depends on the receiver (vsglLambertianRadiance): its scale
// leaves it out.
ShadeLobe diffuseShadeLobe(VsglLobe lobe) {
  return ShadeLobe(lobe.meanVariance, lobe.axisSharpness, colourLogScale(lobe, 0.0));
}

ShadeLobe specularShadeLobe(VsglLobe lobe, vec4 plane) {
  return ShadeLobe(lobe.meanVariance, lobe.axisSharpness,
                   colourLogScale(lobe, log(vsglSpecularNormalisation(lobe, plane))));
}

ShadeLobe broadcastLobe(ShadeLobe lobe, uint lane) {
  return ShadeLobe(subgroupBroadcast(lobe.meanVariance, lane),
                   subgroupBroadcast(lobe.axisSharpness, lane),
                   subgroupBroadcast(lobe.colourLogScale, lane));
}

float largestChannel(vec3 c) {
  return max(c.r, max(c.g, c.b));
}

// The receivers of the subgroup's shaded lanes, as the culling bound sees them: the box of
// their positions, the cone of their normals and the extremes of their materials and views.
// `f0` and `f90` are 0 without the glossy term.
VsglReceivers subgroupReceivers(bool shaded, vec3 position, vec3 normal, vec3 view,
                                float albedo, vec3 f0, float f90, float alpha) {
  const float kHuge = 3.0e38;
  vec3 lo = subgroupMin(shaded ? position : vec3(kHuge));
  vec3 hi = subgroupMax(shaded ? position : vec3(-kHuge));
  VsglReceivers r;
  r.centre = 0.5 * (lo + hi);
  // The half-diagonal of the box, widened by 1e-4 of itself and of |centre| for the rounding
  // of the centre.
  r.radius = 0.5 * length(hi - lo) * 1.0001 + 1e-4 * length(r.centre);
  vec3 sum = subgroupAdd(shaded ? normal : vec3(0.0));
  float length2 = dot(sum, sum);
  r.normalAxis = length2 > 0.0 ? sum * inversesqrt(length2) : vec3(0.0, 0.0, 1.0);
  float cosine = subgroupMin(shaded ? dot(normal, r.normalAxis) : 1.0);
  // Opposed normals sum to about 0: no cone.
  r.normalAngle = length2 > 1e-6 ? min(acos(clamp(cosine, -1.0, 1.0)) + 1e-4, kSgPi) : kSgPi;
  float nv = max(dot(normal, view), kSgGgxMinViewCosine);
  vec2 table = ggxSpecularAlbedo(nv, alpha);
  float specularAlbedo = largestChannel(f90 * table.x + f0 * (table.y - table.x));
  r.albedo = subgroupMax(shaded ? albedo : 0.0);
  r.fresnel = subgroupMax(shaded ? max(largestChannel(f0), f90) : 0.0);
  r.alpha = subgroupMin(shaded ? alpha : 1.0);
  r.viewCosine = subgroupMin(shaded ? nv : 1.0);
  r.specularAlbedo = subgroupMax(shaded ? specularAlbedo : 0.0);
  return r;
}

// Adds one lobe's indirect light (its incoming radiance SG), times the VSGL's visibility, to the
// pixel's sums.
void addLobe(ShadeLobe lobe, Sg radiance, float visibility, vec3 normal, bool glossy,
             SgGgxReceiver ggx, inout vec3 diffuseSum, inout vec3 glossySum) {
  float amplitude = exp(min(radiance.logAmplitude, VSGL_SHADE_MAX_LOG_RADIANCE));
  if (amplitude == 0.0) return;  // no power, or an overlap below fp32 range
  vec3 e = (visibility * amplitude) * lobe.colourLogScale.rgb;
  diffuseSum += e * sgClampedCosineIntegralOverPi(radiance.sharpness, dot(radiance.axis, normal));
  if (glossy) glossySum += e * sgGgxReflection(radiance, ggx);
}

void main() {
  const bool queued = (kFlags & VSGL_SHADE_QUEUE) != 0u;
  // The pixel whose G-buffer is shaded, and where its light is stored: the same pixel, or with
  // a queue, the queued texel of level pc.level at its representative pixel.
  uvec2 pixel = gl_GlobalInvocationID.xy;
  uvec2 target = pixel;
  // No early return: every invocation takes part in the broadcasts below.
  bool inside = all(lessThan(pixel, pc.viewport));
  if (queued) {
    uint index = gl_WorkGroupID.x * ADAPTIVE_QUEUE_GROUP + gl_LocalInvocationIndex;
    uint entry = entries[min(index, head.entries - 1u)];
    inside = index < head.entries && entry != ADAPTIVE_QUEUE_EMPTY;  // padding shades nothing
    if (!inside) entry = 0u;
    target = uvec2(entry & ((1u << ADAPTIVE_PACK_SHIFT) - 1u), entry >> ADAPTIVE_PACK_SHIFT);
    pixel = adaptiveRepresentative(target, pc.level);
  }
  // Above level 0 the level images hold the diffuse term without the albedo, and in alpha the
  // level (diffuse) and 1 for light shaded at the texel's representative pixel (glossy).
  bool modulate = !queued || pc.level == 0u;
  float outAlpha = modulate ? 1.0 : float(pc.level);
  ivec2 store = ivec2(target);
  ivec2 coord = ivec2(min(pixel, pc.viewport - 1u));
  float depth = imageLoad(gDepth, coord).r;
  bool shaded = inside && depth < 1.0;  // depth 1 = sky: never shaded

  vec2 ndc = pixelToNdc(vec2(coord) + 0.5, pc.viewport);
  // Relative to the eye, then moved: no cancellation of |eye| / znear sized terms.
  vec3 receiver = pc.eye + unproject(pc.invViewProjRelative, ndc, depth);
  vec3 origin, direction;
  cameraRay(pc.invViewProjRelative, ndc, origin, direction);
  vec3 view = -direction;
  vec3 normal = octDecode(imageLoad(gNormal, coord).rg);
  // Non-finite material channels read as 0 or 1 (common/finite_material.glsl). The RSM side
  // needs no guard: its attributes pass zeroes non-finite texels.
  vec4 diffuseRoughness = finiteOr(imageLoad(gDiffuse, coord), vec4(0.0, 0.0, 0.0, 1.0));
  vec4 specular = finiteOr(imageLoad(gSpecular, coord), vec4(0.0));  // F0, F90
  // The same alpha floor as the direct light's BRDF (common/brdf.glsl).
  float alpha = max(diffuseRoughness.a * diffuseRoughness.a, 1e-3);
  const bool glossy = (kFlags & VSGL_SHADE_GLOSSY) != 0u;
  const bool diffuseOnly = (kFlags & VSGL_SHADE_DIFFUSE_LOBES) != 0u;  // no specular lobes
  const bool shadowed = (kFlags & VSGL_SHADE_VISIBILITY) != 0u;
  SgGgxReceiver ggx;  // the glossy term's per-pixel part (sg_lighting.glsl)
  if (glossy) ggx = sgGgxReceiver(normal, view, alpha, specular.rgb, specular.a);

  // The planner's sky skip: a subgroup with no pixel to shade has nothing to broadcast for.
  if ((kFlags & VSGL_SHADE_SKIP_SKY) != 0u && subgroupBallotBitCount(subgroupBallot(shaded)) == 0u) {
    if (inside) {
      imageStore(outDiffuse, store, vec4(0.0, 0.0, 0.0, outAlpha));
      imageStore(outGlossy, store, vec4(0.0, 0.0, 0.0, 1.0));
    }
    return;
  }
  vec3 diffuseSum = vec3(0.0);  // sum of E e^(l_p) D, times albedo at the end
  vec3 glossySum = vec3(0.0);
  // VSGLs reach the pixels through registers: each lane of a subgroup loads one VSGL of a block
  // and derives its constants, then the block's VSGLs are broadcast one by one. Every lane runs
  // the loop (sky pixels included) so that each broadcast reads an active lane; `lanes` counts
  // them (all of gl_SubgroupSize unless the subgroup is partial). Measured on lavapipe against a
  // tile of VSGLs in shared memory: 15 % faster shading (memory loads there are per lane).
  uint lanes = subgroupBallotBitCount(subgroupBallot(true));
  // VSGL culling (docs/techniques/vsgl-culling.md): the subgroup is the tile. Per block each
  // lane bounds its VSGL over the subgroup's receivers (common/vsgl_bound.glsl), and VSGLs are
  // skipped in order while their bounds add up to at most pc.cullBudget (tau) of the least light
  // any lane has gathered so far: each pixel loses at most tau of its light. The skip shortens
  // the loop below itself (lavapipe runs both sides of a branch).
  const bool culled = (kFlags & VSGL_SHADE_CULL) != 0u;
  VsglReceivers group;
  if (culled) {
    float albedo = modulate ? max(largestChannel(diffuseRoughness.rgb), 0.0) : 1.0;
    vec4 fresnel = glossy ? specular : vec4(0.0);
    group = subgroupReceivers(shaded, receiver, normal, view, albedo, fresnel.rgb, fresnel.a, alpha);
  }
  float skippedBound = 0.0;  // the bounds of the VSGLs skipped so far
  uint tested = 0u, skipped = 0u;
  for (uint first = 0u; first < pc.vsglCount; first += lanes) {
    uint count = min(lanes, pc.vsglCount - first);
    Vsgl mine = vsgls[first + min(gl_SubgroupInvocationID, count - 1u)];
    float myBeta = vsglEmitterPlanarity(mine, (kFlags & VSGL_SHADE_PLANAR) != 0u);
    vec4 myPlane = vsglEmitterPlane(mine.diffuse.axisSharpness.xyz, myBeta);
    ShadeLobe myDiffuse = diffuseShadeLobe(mine.diffuse);
    ShadeLobe mySpecular = specularShadeLobe(mine.specular, myPlane);
    IsmFrame myFrame = ismFrame(mine, pc.ism.centreOffset);
    bool valid = gl_SubgroupInvocationID < count;
    uvec4 keep = subgroupBallot(valid);
    if (culled) {
      vec3 light = (modulate ? diffuseSum * diffuseRoughness.rgb : diffuseSum) + glossySum;
      float budget = pc.cullBudget * subgroupMin(shaded ? largestChannel(light) : 3.0e38) - skippedBound;
      // The diffuse lobe's emission sharpness lies in [(1 - beta) lambda, lambda] and its N is
      // least at lambda: the bound takes the widest emission with the least N. Foreshortening
      // only lowers the light (f <= 1, docs/techniques/planar-emitters.md).
      float diffuseSharpness = myDiffuse.axisSharpness.w;
      vec2 bound = vsglLobeBound(
          myDiffuse.meanVariance.xyz, myDiffuse.meanVariance.w, myDiffuse.axisSharpness.xyz,
          myPlane.w * diffuseSharpness,
          myDiffuse.colourLogScale.a - log(vsglLambertianNormalisation(diffuseSharpness, myPlane)),
          group);
      if (!diffuseOnly)
        bound += vsglLobeBound(mySpecular.meanVariance.xyz, mySpecular.meanVariance.w,
                               mySpecular.axisSharpness.xyz, mySpecular.axisSharpness.w,
                               mySpecular.colourLogScale.a, group);
      float total = bound.x + bound.y;
      // Lanes in order: a candidate is skipped while the running sum stays within the budget
      // (NaN or +inf bounds never are).
      bool candidate = valid && total <= budget;
      float prefix = subgroupInclusiveAdd(candidate ? total : 0.0);
      bool skip = candidate && prefix <= budget;
      skippedBound += subgroupMax(skip ? prefix : 0.0);
      keep = subgroupBallot(valid && !skip);
      tested += count;
      skipped += subgroupBallotBitCount(subgroupBallot(skip));
    }
    while (any(notEqual(keep, uvec4(0u)))) {
      uint j = subgroupBallotFindLSB(keep);
      keep[j >> 5u] &= ~(1u << (j & 31u));
      // As few scalars broadcast as can be (common/ism_broadcast.glsl says why): the plane is
      // rebuilt from the diffuse axis and beta, and without specular lobes a lit frame's axis
      // is the diffuse one (common/ism_lookup.glsl, ismFrameFromLobes).
      ShadeLobe diffuseLobe = broadcastLobe(myDiffuse, j);
      vec3 diffuseAxis = diffuseLobe.axisSharpness.xyz;
      vec4 plane = vsglEmitterPlane(diffuseAxis, subgroupBroadcast(myBeta, j));
      IsmFrame frame = diffuseOnly ? broadcastFrame(myFrame, diffuseAxis, j)
                                   : broadcastFrame(myFrame, j);
      ShadeLobe specularLobe;
      if (!diffuseOnly) specularLobe = broadcastLobe(mySpecular, j);
      if (!shaded) continue;
      // One test per VSGL: both lobes share its map.
      float visibility = shadowed ? ismVisibility(pc.ism, frame, first + j, receiver, normal) : 1.0;
      if (visibility == 0.0) continue;
      Sg diffuseRadiance = vsglLambertianRadiance(
          diffuseLobe.meanVariance.xyz, diffuseLobe.meanVariance.w, diffuseLobe.axisSharpness.xyz,
          diffuseLobe.axisSharpness.w, diffuseLobe.colourLogScale.a, receiver, normal, plane);
      addLobe(diffuseLobe, diffuseRadiance, visibility, normal, glossy, ggx, diffuseSum,
              glossySum);
      if (!diffuseOnly) {
        Sg specularRadiance = vsglIncomingRadiance(
            specularLobe.meanVariance.xyz, specularLobe.meanVariance.w,
            specularLobe.axisSharpness.xyz, specularLobe.axisSharpness.w,
            specularLobe.colourLogScale.a, receiver, plane);
        addLobe(specularLobe, specularRadiance, visibility, normal, glossy, ggx, diffuseSum,
                glossySum);
      }
    }
  }
  bool counted = culled && subgroupAny(shaded);
  if (counted && subgroupElect()) {
    atomicAdd(stats.tested[pc.level], tested);
    atomicAdd(stats.skipped[pc.level], skipped);
  }
  if (inside) {
    vec3 diffuse = modulate ? diffuseSum * diffuseRoughness.rgb : diffuseSum;
    imageStore(outDiffuse, store, vec4(shaded ? diffuse : vec3(0.0), outAlpha));
    imageStore(outGlossy, store, vec4(shaded ? glossySum : vec3(0.0), 1.0));
  }
}
