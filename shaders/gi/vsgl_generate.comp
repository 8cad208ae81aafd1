#version 460
// VSGL generation by filtered importance sampling, one thread per VSGL (vsgl-math.md 5-6):
// Fibonacci lattice point -> hierarchical warp down the PDF pyramid -> kernel level (Tok15 or
// modified FIS bisection) -> the six attribute pyramids filtered with that kernel -> two lobes.
// Trilinear filtering is done by hand from texelFetch with exact fp32 weights: the bisection
// compares filtered masses, and the sampler's fixed-point weights would blur the comparison.
// VSGL_RULE_POINT makes the VPL baseline's point lights instead: one texel each.
// The CPU twin is generateVsglsReference (gi/src/reference/vsgl_sampling.cpp).
#extension GL_GOOGLE_include_directive : require

#include "shared/vsgl.h"
#include "shared/vsgl_allocation.h"
#include "shared/vsgl_attributes.h"
#include "shared/vsgl_generate.h"
#include "common/vsgl_lobes.glsl"

layout(local_size_x = VSGL_GENERATE_GROUP) in;

#include "common/attribute_pyramids.glsl"
layout(std430, binding = VSGL_ATTR_COUNT) writeonly buffer Vsgls { Vsgl vsgls[]; };
layout(std430, binding = VSGL_ATTR_COUNT + 1) readonly buffer Ranges { VsglViewRange ranges[]; };
layout(push_constant) uniform Push { VsglGeneratePush pc; };

// N of this view: the push constant's, or its share of the frame's (vsgl_allocate.comp).
uint viewCount() { return pc.ranged != 0u ? ranges[pc.view].range.y : pc.count; }

#include "common/lattice_warp.glsl"
#include "common/fis_kernel.glsl"

vec4 bilinear(sampler2D s, vec2 x, int level) {
  BilinearTaps b = bilinearTaps(x, int(pc.size) >> level);
  return bilinearBlend(b, texelFetch(s, b.i0, level), texelFetch(s, ivec2(b.i1.x, b.i0.y), level),
                       texelFetch(s, ivec2(b.i0.x, b.i1.y), level), texelFetch(s, b.i1, level));
}

vec4 trilinear(sampler2D s, vec2 x, float level) {
  int l0, l1;
  float upper;
  trilinearLevels(level, int(pc.topLevel), l0, l1, upper);
  return mix(bilinear(s, x, l0), bilinear(s, x, l1), upper);
}

float gPdfTop = 1.0;  // fisKernelMass's normalisation: the PDF's top-level mean

// PDF mass inside a level-l kernel at x: 4^l p~(x, l) / (M p_top) ([S3] Eq. 3's left side).
float fisKernelMass(vec2 x, float level) {
  float m = float(pc.size) * float(pc.size);
  return exp2(2.0 * level) * trilinear(diffuseAxis, x, level).w / (gPdfTop * m);
}

float modifiedFisLevel(vec2 x, float pTop) {
  gPdfTop = pTop;
  // Below a kernel scale of N some kernel is large enough; else every kernel is the whole map.
  return modifiedFisBisection(x, pc.kernelScale / float(viewCount()), float(pc.topLevel),
                              pc.kernelScale < float(viewCount()));
}

// Tok15 ([S3] Eq. 1 with K): 4^l / M = K / (N p) with the unfiltered density at the centre.
float tok15Level(float density) {
  float top = float(pc.topLevel);
  if (!(density > 0.0)) return top;
  float m = float(pc.size) * float(pc.size);
  return clamp(0.5 * log2(pc.kernelScale * m / (float(viewCount()) * density)), 0.0, top);
}

// VSGL_RULE_POINT: the area of the surface patch one texel covers at offset y from the origin
// with unit normal n: its solid angle from the light (A cos^3 on the unit-distance plane) times
// t^2 / cos at the surface, or a parallel beam's A / cos (the CPU twin is vplTexelArea). n = 0
// (a texel without diffuse power keeps no normal): the patch faces the light.
float texelPatchArea(vec3 y, vec3 n) {
  bool perspective = pc.perspective != 0u;
  vec3 w = perspective ? normalize(y) : pc.texelPatch.xyz;  // light -> surface
  float cosine = dot(n, n) > 0.0 ? max(abs(dot(n, w)), 1e-6) : 1.0;
  if (!perspective) return pc.texelPatch.w / cosine;
  float c = dot(w, pc.texelPatch.xyz);
  return pc.texelPatch.w * c * c * c * dot(y, y) / cosine;
}

// Kernels that leave their surface (docs/techniques/vsgl-generation.md): a kernel of the light's
// image that spans a depth discontinuity (a pillar's top and the floor beside it) has its mean
// between the two surfaces, and its one Gaussian lights the room from mid-air. Whether the
// kernel's mean at `level` lies more than pc.surfaceTolerance standard deviations (per axis, as
// the lobe's variance) off the plane through `surface`, the lit surface under the kernel's
// centre, with the diffuse lobe's mean normal. The offset is weighted by the kernel's planarity
// (the planar emitters' beta of its diffuse sharpness): a corner's mean lies off both its faces
// by nature, and its SG emitter is not cut by a plane. A kernel without diffuse weight has no
// plane.
bool offSurface(vec2 x, float level, vec3 surface) {
  float wd = trilinear(diffusePower, x, level).a;
  float w = wd + trilinear(specularPower, x, level).a;
  vec3 axis = trilinear(diffuseAxis, x, level).xyz;
  if (!(wd > 0.0) || !(dot(axis, axis) > 0.0)) return false;
  vec4 sums = trilinear(diffusePosition, x, level) + trilinear(specularPosition, x, level);
  vec3 mean = sums.xyz / w;
  float variance = max(sums.w / w - dot(mean, mean), 0.0) * 0.5;
  vec3 unitAxis;
  float sharpness;
  lobeFromMeanAxis(axis / wd, unitAxis, sharpness);
  float beta = vsglPlanarity(sharpness);
  float h = beta * dot(mean - surface, unitAxis);
  float t = pc.surfaceTolerance;
  return h * h > t * t * variance;
}

// The lowest level at which the kernel leaves its surface, or `level` if it stays on it up to
// there: a scan up from level 0 (where the kernel's mean is the surface itself) in quarter
// levels, then bisection within the first quarter that leaves. The first crossing, not any
// crossing: it moves continuously with x where a bisection over [0, level] could jump between
// crossings.
float surfaceLevel(vec2 x, float level, vec3 surface) {
  float lo = 0.0;
  while (lo < level) {
    float hi = min(lo + VSGL_SURFACE_SCAN_STEP, level);
    if (offSurface(x, hi, surface)) {
      for (int step = 0; step < VSGL_SURFACE_BISECTION_STEPS; ++step) {
        float mid = 0.5 * (lo + hi);
        if (offSurface(x, mid, surface)) hi = mid; else lo = mid;
      }
      return lo;
    }
    lo = hi;
  }
  return level;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint count = viewCount();
  if (i >= count) return;
  uint first = pc.ranged != 0u ? ranges[pc.view].range.x : 0u;
  vec2 u = fibonacciPoint(i, count);
  ivec2 node = warpToTexel(u, int(pc.topLevel));
  float size = float(pc.size);
  bool point = pc.rule == VSGL_RULE_POINT;
  // A VPL reads its texel alone: level 0 at the texel's centre, where the bilinear weights are
  // exactly 0 and 1 (a power-of-two size scales the centre exactly).
  vec2 x = point ? (vec2(node) + 0.5) / size : min((vec2(node) + u) / size, (vec2(node) + kOneBelow) / size);
  float pTop = pdfTexel(ivec2(0), int(pc.topLevel));
  float density = pTop > 0.0 ? pdfTexel(node, 0) / pTop : 0.0;
  bool modified = pc.rule == VSGL_RULE_MODIFIED;
  float level = point ? 0.0 : modified ? modifiedFisLevel(x, pTop) : tok15Level(density);
  // The surface under x: the power-weighted level-0 position bilinearly around it, which moves
  // continuously with x. It is also the ISM's centre (docs/techniques/ism.md, "The map's centre").
  float surfaceWeight = bilinear(diffusePower, x, 0).a + bilinear(specularPower, x, 0).a;
  vec3 surface = (bilinear(diffusePosition, x, 0).xyz + bilinear(specularPosition, x, 0).xyz) /
                 max(surfaceWeight, 1e-30);
  if (pc.surfaceTolerance > 0.0 && surfaceWeight > 0.0) level = surfaceLevel(x, level, surface);
  // The diffuse axis sums carry the PDF in alpha: one filtered fetch serves both.
  vec4 diffuseAxisSums = trilinear(diffuseAxis, x, level);
  float filtered = pTop > 0.0 ? diffuseAxisSums.w / pTop : 0.0;
  // Cluster sums from per-texel means (vsgl-math.md 5.3 units trap): modified FIS scales the
  // kernel to mass 1/N, M / (N p~); Tok15 divides by the unfiltered density, M / max(N p, 1);
  // a VPL is the texel's own value over N p, the estimator of importance sampling.
  float m = size * size;
  float scale = !(pTop > 0.0) ? 0.0
              : modified || point ? (filtered > 0.0 ? m / (float(count) * filtered) : 0.0)
                                  : m / max(float(count) * density, 1.0);
  Vsgl v;
  v.diffuse = buildVsglLobe(scale * trilinear(diffusePower, x, level),
                        scale * trilinear(diffusePosition, x, level),
                        scale * diffuseAxisSums, pc.origin.xyz);
  v.specular = buildVsglLobe(scale * trilinear(specularPower, x, level),
                         scale * trilinear(specularPosition, x, level),
                         scale * trilinear(specularAxis, x, level), pc.origin.xyz);
  // A VPL with power stands for 1 / (N p) of the texel, but never for less than the texel
  // itself: as N grows it becomes the texel, and the VPL image the gather over every texel. Its
  // disc of area a has the per-axis variance a / (4 pi) (docs/techniques/vpl-baseline.md).
  if (point && v.diffuse.power.a + v.specular.power.a > 0.0) {
    bool hasNormal = v.diffuse.power.a > 0.0;
    vec3 mean = hasNormal ? v.diffuse.meanVariance.xyz : v.specular.meanVariance.xyz;
    vec3 normal = hasNormal ? v.diffuse.axisSharpness.xyz : vec3(0.0);
    float area = texelPatchArea(mean - pc.origin.xyz, normal) * max(1.0, scale);
    v.diffuse.meanVariance.w = v.specular.meanVariance.w = area / 12.566370614359172;  // 4 pi
  }
  v.kernel = vec4(x, level, filtered);
  v.visibilityPoint = surfaceWeight > 0.0 ? vec4(pc.origin.xyz + surface, 1.0) : vec4(0.0);
  vsgls[first + i] = v;
}
