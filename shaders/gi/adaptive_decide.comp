#version 460
// One level of adaptive shading (shaders/shared/adaptive_shading.h, docs/techniques/
// adaptive-shading.md): each texel of level L either takes its light from its four parents at
// level L + 1 by bilinear interpolation, or joins the level's queue to be shaded. It is
// interpolated only when every parent sees the same surface and material ([S4] section 3.2
// weights parents by a depth Gaussian; here a parent off the texel's surface sends the texel to
// be shaded instead, so light never bleeds across an edge) and the parents' light agrees within
// the tolerance (a measured stand-in for [S4]'s predicted bandwidth, vsgl-math.md section 11).
// A texel that cannot interpolate but whose representative pixel is its first parent's, where
// that parent's light was shaded, reuses that light. Every texel of the coarsest level is
// shaded. The CPU twin is
// gi/src/reference/adaptive_reference.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/adaptive_shading.h"
#include "common/camera_ray.glsl"
#include "common/color.glsl"
#include "common/finite_material.glsl"
#include "common/octahedral.glsl"

layout(local_size_x = ADAPTIVE_GROUP_X, local_size_y = ADAPTIVE_GROUP_Y) in;

layout(binding = 0, r32f) uniform readonly image2D gDepth;
layout(binding = 1, rg16_snorm) uniform readonly image2D gNormal;
layout(binding = 2, rgba16f) uniform readonly image2D gDiffuse;
layout(binding = 3, rgba16f) uniform readonly image2D gSpecular;
// Level L + 1 (not read at the coarsest level): rgb = diffuse light without the albedo, or
// glossy light; diffuse a = the level the light was shaded at, glossy a = 1 when it was shaded
// at this texel's representative pixel (shaded or reused), 0 when interpolated.
layout(binding = 4, rgba32f) uniform readonly image2D parentDiffuse;
layout(binding = 5, rgba32f) uniform readonly image2D parentGlossy;
// Level L in the same form, or at level 0 the module's outputs (albedo applied, alpha 1).
layout(binding = 6, rgba32f) uniform writeonly image2D outDiffuse;
layout(binding = 7, rgba32f) uniform writeonly image2D outGlossy;
layout(std430, binding = 8) buffer Queue {
  AdaptiveQueueHeader head;
  uint entries[];
};
// The texels to shade without the glossy term (F0 = F90 = 0), when pc.splitGlossy is set.
layout(std430, binding = 10) buffer PlainQueue {
  AdaptiveQueueHeader plainHead;
  uint plainEntries[];
};
// Level 0 only: the level each pixel's light was shaded at, -1 for the sky (a debug view).
layout(binding = 9, r32f) uniform writeonly image2D outLevels;
layout(push_constant) uniform Push { AdaptiveDecidePush pc; };

// What the tests read of a representative pixel, its position relative to the eye.
struct Surface {
  bool sky;
  vec3 position;
  vec3 normal;
  vec3 albedo;
  float roughness;
  vec3 f0;
  float f90;
};

Surface surfaceAt(uvec2 pixel) {
  ivec2 coord = ivec2(pixel);
  float depth = imageLoad(gDepth, coord).r;
  vec4 diffuseRoughness = imageLoad(gDiffuse, coord);
  Surface s;
  s.sky = !(depth < 1.0);
  s.position = unproject(pc.invViewProjRelative, pixelToNdc(vec2(pixel) + 0.5, pc.viewport), depth);
  s.normal = octDecode(imageLoad(gNormal, coord).rg);
  s.albedo = diffuseRoughness.rgb;
  s.roughness = diffuseRoughness.a;
  vec4 specular = imageLoad(gSpecular, coord);
  s.f0 = specular.rgb;
  s.f90 = specular.a;
  return s;
}

// The parent lies on the texel's surface (within planeTolerance of the parent's tangent plane,
// relative to the texel's distance, and normals within the cone) and has its material. Written
// so that a NaN anywhere fails the test: such a texel is shaded, and shading guards it.
bool sameSurface(Surface s, Surface parent) {
  vec4 specularChange = abs(vec4(s.f0, s.f90) - vec4(parent.f0, parent.f90));
  return !parent.sky &&
         abs(dot(parent.normal, s.position - parent.position)) <=
             pc.planeTolerance * length(s.position) &&
         dot(s.normal, parent.normal) >= pc.normalCosine &&
         abs(s.roughness - parent.roughness) <= pc.roughnessTolerance &&
         max(max(specularChange.r, specularChange.g), max(specularChange.b, specularChange.a)) <=
             pc.f0Tolerance;
}

// Which queue a texel joins.
const uint kNotQueued = 0u, kGlossyQueue = 1u, kPlainQueue = 2u;

// Decides one texel of the level: writes its light where it is interpolated, reused or sky, and
// returns the queue it joins otherwise.
uint decideTexel(uvec2 texel) {
  ivec2 store = ivec2(texel);
  uvec2 pixel = adaptiveRepresentative(texel, pc.level);
  Surface s = surfaceAt(pixel);
  float alpha = pc.level == 0u ? 1.0 : 0.0;  // level 0: the module's outputs, alpha 1
  if (s.sky) {
    imageStore(outDiffuse, store, vec4(0.0, 0.0, 0.0, alpha));
    imageStore(outGlossy, store, vec4(0.0, 0.0, 0.0, alpha));
    if (pc.level == 0u) imageStore(outLevels, store, vec4(-1.0));
    atomicAdd(head.sky, 1u);
    return kNotQueued;
  }

  bool interpolate = pc.level < pc.coarsest;
  bool reuse = false;
  vec3 diffuse = vec3(0.0), glossy = vec3(0.0);
  uint origin = 0u;
  if (interpolate) {
    // The 2 x 2 parents around the pixel, bilinear weights from the parents' representative
    // pixels (j 2^(L+1)); past the last parent the weights stop at 1.
    uint parentLevel = pc.level + 1u;
    ivec2 parentSize = ivec2(adaptiveLevelSize(pc.viewport.x, parentLevel),
                             adaptiveLevelSize(pc.viewport.y, parentLevel));
    ivec2 first = ivec2(texel >> 1u);
    ivec2 last = min(first + 1, parentSize - 1);
    vec2 t = clamp((vec2(pixel) - vec2(adaptiveRepresentative(uvec2(first), parentLevel))) /
                       max(vec2(adaptiveRepresentative(uvec2(last - first), parentLevel)), vec2(1.0)),
                   0.0, 1.0);
    float lightMin = 1.0 / 0.0, lightMax = 0.0, lightSum = 0.0, largest = -1.0;
    vec4 firstDiffuse, firstGlossy;  // parent k = 0, for the reuse below
    for (uint k = 0u; k < 4u; ++k) {
      bvec2 upper = bvec2((k & 1u) != 0u, (k & 2u) != 0u);
      ivec2 parent = mix(first, last, upper);
      vec2 w2 = mix(1.0 - t, t, upper);
      float w = w2.x * w2.y;
      Surface p = surfaceAt(adaptiveRepresentative(uvec2(parent), parentLevel));
      if (!sameSurface(s, p)) interpolate = false;
      vec4 d = imageLoad(parentDiffuse, parent);
      vec4 g4 = imageLoad(parentGlossy, parent);
      vec3 g = g4.rgb;
      if (k == 0u) {
        firstDiffuse = d;
        firstGlossy = g4;
      }
      // The light the texel would show from this parent: its albedo times the diffuse term.
      float light = luminance(d.rgb * s.albedo) + luminance(g);
      lightMin = min(lightMin, light);
      lightMax = max(lightMax, light);
      lightSum += light;
      diffuse += w * d.rgb;
      glossy += w * g;
      if (w > largest) {
        largest = w;
        origin = uint(d.a);
      }
    }
    // (NaN light fails the test too.)
    if (!(lightMax - lightMin <= pc.lightTolerance * 0.25 * lightSum)) interpolate = false;
    // An even texel shares its representative pixel with its first parent: when that parent's
    // light was shaded there, it is this texel's light too.
    if (!interpolate && all(equal(texel & 1u, uvec2(0u)))) {
      reuse = firstGlossy.a == 1.0;
      diffuse = firstDiffuse.rgb;
      glossy = firstGlossy.rgb;
      origin = uint(firstDiffuse.a);
    }
  }
  if (!interpolate && !reuse) {
    // No glossy term where F0 and F90 are 0, as the shading reads them (non-finite = 0).
    vec4 specular = finiteOr(vec4(s.f0, s.f90), vec4(0.0));
    if (pc.level == 0u) imageStore(outLevels, store, vec4(0.0));
    return pc.splitGlossy != 0u && all(equal(specular, vec4(0.0))) ? kPlainQueue : kGlossyQueue;
  }
  if (reuse)
    atomicAdd(head.reused, 1u);
  else
    atomicAdd(head.interpolated, 1u);
  if (pc.level == 0u) {
    atomicAdd(head.fromLevel[min(origin, ADAPTIVE_MAX_LEVEL)], 1u);
    imageStore(outLevels, store, vec4(float(origin)));
    // A reused texel skipped the light test that a non-finite albedo fails: such an albedo
    // reads as 0, as in the shading (vsgl_shade.comp; vsgl-math.md section 12, case 14).
    vec3 albedo = finiteOr(s.albedo, vec3(0.0));
    imageStore(outDiffuse, store, vec4(diffuse * albedo, 1.0));
    imageStore(outGlossy, store, vec4(glossy, 1.0));
  } else {
    imageStore(outDiffuse, store, vec4(diffuse, float(origin)));
    imageStore(outGlossy, store, vec4(glossy, reuse ? 1.0 : 0.0));
  }
  return kNotQueued;
}

// Appends `count` entries to a queue: returns the first index (entries counts the padding,
// shaded does not) and grows the queue's dispatch to cover them.
uint reserve(uint queue, uint count, uint padded) {
  if (queue == kPlainQueue) {
    uint first = atomicAdd(plainHead.entries, padded);
    atomicAdd(plainHead.shaded, count);
    atomicMax(plainHead.groupsX, (first + padded + ADAPTIVE_QUEUE_GROUP - 1u) / ADAPTIVE_QUEUE_GROUP);
    return first;
  }
  uint first = atomicAdd(head.entries, padded);
  atomicAdd(head.shaded, count);
  atomicMax(head.groupsX, (first + padded + ADAPTIVE_QUEUE_GROUP - 1u) / ADAPTIVE_QUEUE_GROUP);
  return first;
}

void store(uint queue, uint index, uint entry) {
  if (queue == kPlainQueue)
    plainEntries[index] = entry;
  else
    entries[index] = entry;
}

// Ordered queues (pc.orderedAlign > 0): the group's texels of each queue, in invocation order.
shared uint groupQueue[ADAPTIVE_GROUP_X * ADAPTIVE_GROUP_Y];

void main() {
  uvec2 size = uvec2(adaptiveLevelSize(pc.viewport.x, pc.level),
                     adaptiveLevelSize(pc.viewport.y, pc.level));
  uvec2 texel = gl_GlobalInvocationID.xy;
  uint queue = all(lessThan(texel, size)) ? decideTexel(texel) : kNotQueued;
  uint entry = texel.x | (texel.y << ADAPTIVE_PACK_SHIFT);
  if (pc.orderedAlign == 0u) {  // each texel appends itself, in whatever order the device runs
    if (queue != kNotQueued) store(queue, reserve(queue, 1u, 1u), entry);
    return;
  }
  // One invocation appends the group's texels of each queue as one range, in invocation order,
  // padded with empty entries to a multiple of orderedAlign, the shading's subgroup size: each
  // subgroup of the shading pass then holds the same texels in every run, however the groups'
  // ranges are ordered, and VSGL culling, which decides per subgroup, is deterministic.
  groupQueue[gl_LocalInvocationIndex] = queue;
  barrier();
  if (gl_LocalInvocationIndex != 0u) return;
  const uint invocations = ADAPTIVE_GROUP_X * ADAPTIVE_GROUP_Y;
  for (uint q = kGlossyQueue; q <= kPlainQueue; ++q) {
    uint count = 0u;
    for (uint i = 0u; i < invocations; ++i) count += groupQueue[i] == q ? 1u : 0u;
    if (count == 0u) continue;
    uint padded = (count + pc.orderedAlign - 1u) / pc.orderedAlign * pc.orderedAlign;
    uint next = reserve(q, count, padded);
    uvec2 origin = gl_WorkGroupID.xy * uvec2(ADAPTIVE_GROUP_X, ADAPTIVE_GROUP_Y);
    for (uint i = 0u; i < invocations; ++i) {
      if (groupQueue[i] != q) continue;
      uvec2 t = origin + uvec2(i % ADAPTIVE_GROUP_X, i / ADAPTIVE_GROUP_X);
      store(q, next++, t.x | (t.y << ADAPTIVE_PACK_SHIFT));
    }
    for (uint i = count; i < padded; ++i) store(q, next++, ADAPTIVE_QUEUE_EMPTY);
  }
}
