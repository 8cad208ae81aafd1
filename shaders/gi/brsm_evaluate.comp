#version 460
// BRSM stage B (shaders/shared/brsm.h): the importance that each RSM cell's diffuse and glossy
// lobes reflect toward the camera, from the importance VSGLs. One thread per cell; the loop over
// importance VSGLs is the cost (cells x importance VSGLs x 2 x 2 SG inner products). The CPU
// twin is gi/src/reference/brsm_reference.cpp.
//
// Without specular lobes (kSpecular off: the planner's choice for a scene where no surface has a
// specular lobe, whose specular pyramids are then all zero) the importance VSGLs' specular lobes
// carry no power and no texel has glossy weight, so only the diffuse lobes are read and only I_d
// is evaluated: a quarter of the inner products, the same I_d and PDF to the bit (the dropped
// terms were exact zeros), and I_s = 0.
#extension GL_GOOGLE_include_directive : require

#include "shared/brsm.h"
#include "shared/vsgl.h"
#include "shared/vsgl_attributes.h"
#include "common/sg.glsl"
#include "common/vsgl_lobes.glsl"

layout(local_size_x = BRSM_GROUP_X, local_size_y = BRSM_GROUP_Y) in;

// Bindings VSGL_ATTR_*: the light's attribute pyramids; only the cell level is read.
layout(binding = VSGL_ATTR_DIFFUSE_POWER, rgba32f) uniform readonly image2D diffusePower;
layout(binding = VSGL_ATTR_DIFFUSE_POSITION, rgba32f) uniform readonly image2D diffusePosition;
layout(binding = VSGL_ATTR_DIFFUSE_AXIS, rgba32f) uniform readonly image2D diffuseAxis;
layout(binding = VSGL_ATTR_SPECULAR_POWER, rgba32f) uniform readonly image2D specularPower;
layout(binding = VSGL_ATTR_SPECULAR_POSITION, rgba32f) uniform readonly image2D specularPosition;
layout(binding = VSGL_ATTR_SPECULAR_AXIS, rgba32f) uniform readonly image2D specularAxis;
layout(std430, binding = VSGL_ATTR_COUNT) readonly buffer Importance { Vsgl importance[]; };
layout(binding = VSGL_ATTR_COUNT + 1, rgba32f) uniform writeonly image2D outCells;
layout(push_constant) uniform Push { BrsmEvaluatePush pc; };
layout(constant_id = 0) const bool kSpecular = true;

// A tile of importance lobes in shared memory, with the per-lobe constants of the incoming SG
// (section 4.1) computed once per tile instead of once per cell: every cell of the group reads
// the same lobes (measured on lavapipe: 350 -> 290 ms at 64^2 cells x 2048 VSGLs).
const uint kTile = BRSM_GROUP_X * BRSM_GROUP_Y;  // VSGLs per tile
const uint kLobesPerVsgl = kSpecular ? 2u : 1u;
shared vec4 tileMeanVariance[2 * kTile];
shared vec4 tileAxisSharpness[2 * kTile];
// log(power / (2 pi S(sharpness))); -inf for a lobe without power, whose terms are then exp(-inf) = 0.
shared float tileLogScale[2 * kTile];

void loadLobe(uint slot, VsglLobe lobe) {
  tileMeanVariance[slot] = lobe.meanVariance;
  tileAxisSharpness[slot] = lobe.axisSharpness;
  float power = lobe.power.a;
  tileLogScale[slot] = power > 0.0
      ? log(power) - log(2.0 * kSgPi) - log(sgIntegral(lobe.axisSharpness.w))
      : -1.0 / 0.0;
}

void main() {
  uvec2 cell = gl_GlobalInvocationID.xy;
  // No early return: every invocation takes part in the tile barriers.
  bool inside = all(lessThan(cell, uvec2(pc.gridSize)));
  ivec2 c = ivec2(min(cell, uvec2(pc.gridSize - 1u)));
  // Per-texel means at the cell level; ratios of two of them are exact cluster means.
  float wd = imageLoad(diffusePower, c).a;
  float ws = imageLoad(specularPower, c).a;
  bool lit = inside && wd + ws > 0.0;
  vec3 receiver = vec3(0.0);
  Sg diffuseLobe = Sg(vec3(0.0, 0.0, 1.0), 0.0, 0.0), glossyLobe = diffuseLobe;
  if (lit) {
    // One receiver point per cell: the mean position of both lobes' weight.
    receiver = pc.origin.xyz +
               (imageLoad(diffusePosition, c).xyz + imageLoad(specularPosition, c).xyz) / (wd + ws);
    lobeFromMeanAxis(wd > 0.0 ? imageLoad(diffuseAxis, c).xyz / wd : vec3(0.0),
                     diffuseLobe.axis, diffuseLobe.sharpness);
    lobeFromMeanAxis(ws > 0.0 ? imageLoad(specularAxis, c).xyz / ws : vec3(0.0),
                     glossyLobe.axis, glossyLobe.sharpness);
  }
  // The cell lobes as vMFs: SGs whose integral over the sphere is 1.
  float diffuseLogNorm = -log(sgIntegral(diffuseLobe.sharpness));
  float glossyLogNorm = -log(sgIntegral(glossyLobe.sharpness));

  vec2 sums = vec2(0.0);
  for (uint base = 0u; base < pc.importanceCount; base += kTile) {
    uint k = base + gl_LocalInvocationIndex;
    uint slot = kLobesPerVsgl * gl_LocalInvocationIndex;
    if (k < pc.importanceCount) {
      loadLobe(slot, importance[k].diffuse);
      if (kSpecular) loadLobe(slot + 1u, importance[k].specular);
    } else {
      tileLogScale[slot] = -1.0 / 0.0;
      if (kSpecular) tileLogScale[slot + 1u] = -1.0 / 0.0;
    }
    barrier();
    uint lobes = kLobesPerVsgl * min(kTile, pc.importanceCount - base);
    if (lit) {
      for (uint j = 0u; j < lobes; ++j) {
        vec4 meanVariance = tileMeanVariance[j];
        vec4 axisSharpness = tileAxisSharpness[j];
        Sg incoming = vsglIncomingRadiance(meanVariance.xyz, meanVariance.w, axisSharpness.xyz,
                                           axisSharpness.w, tileLogScale[j], receiver,
                                           vec4(0.0, 0.0, 0.0, 1.0));
        sums.x += sgInnerProduct(incoming, diffuseLobe, diffuseLogNorm);
        if (kSpecular) sums.y += sgInnerProduct(incoming, glossyLobe, glossyLogNorm);
      }
    }
    barrier();
  }
  if (!inside) return;
  sums = min(sums, vec2(BRSM_MAX_IMPORTANCE));
  imageStore(outCells, c, lit ? vec4(sums, sums.x * wd + sums.y * ws, 0.0) : vec4(0.0));
}
