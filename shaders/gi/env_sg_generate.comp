#version 460
// SG lights from the environment by modified filtered importance sampling, one thread per light
// (docs/techniques/environment.md pass 4; vsgl-math.md sections 3, 5.3 and 6, the VSGL path of
// vsgl_generate.comp on the environment's luminance x solid-angle PDF):
//   Fibonacci lattice point i of N -> a split between the two layers by their PDF mass, then the
//   hierarchical warp down the chosen layer's PDF quadtree -> the kernel level at which the
//   kernel holds K / N of the PDF mass (bisection, trilinear) -> the kernel's sums at that level
//   -> the axis at the sample's own direction, Banerjee sharpness from the luminance-weighted
//   mean direction, amplitude from the light's share of the radiance integral,
//   Phi = M m_top rgb~ / (N m~) (derived in
//   gi/src/reference/env_sg_reference.h), times 4 pi / sum w over S(sharpness).
// Trilinear reads are done by hand from texelFetch with exact fp32 weights, as in
// vsgl_generate.comp. CPU twin: gi::generateEnvSgLightsReference.
//
// This work is based on:
//   [S3]  Tokuyoshi, "Modified Filtered Importance Sampling for Virtual Spherical Gaussian
//         Lights", 2016 (Eqs. 2, 3 and 5: kernels of mass K / N, the estimator f~ / (N p~)).
//   [C05] Clarberg et al., "Wavelet Importance Sampling", 2005 (hierarchical warping).
//   [B05] Banerjee et al., 2005 (the vMF sharpness estimate of a mean resultant length).
#extension GL_GOOGLE_include_directive : require

#include "shared/vsgl.h"
#include "shared/env_sg.h"
#include "shared/environment.h"
#include "common/vsgl_lobes.glsl"
#include "common/sg.glsl"
#include "common/env_paraboloid.glsl"

layout(local_size_x = ENV_SG_GENERATE_GROUP) in;

layout(binding = 0) uniform sampler2DArray radiancePyramid;   // ENV_SG_RADIANCE
layout(binding = 1) uniform sampler2DArray directionPyramid;  // ENV_SG_DIRECTION
layout(std430, binding = 2) writeonly buffer Lights { EnvSgLight lights[]; };
layout(push_constant) uniform Push { EnvSgGeneratePush pc; };

// The layer that the warp walks (lattice_warp.glsl's pdfTexel has no layer argument).
int gLayer = 0;

// The PDF mass m_t = w lum (per-texel mean at `level`) of a texel of gLayer.
float pdfTexel(ivec2 texel, int level) {
  return texelFetch(radiancePyramid, ivec3(texel, gLayer), level).a;
}

#include "common/lattice_warp.glsl"
#include "common/fis_kernel.glsl"

vec4 bilinear(sampler2DArray s, vec2 x, int layer, int level) {
  BilinearTaps b = bilinearTaps(x, int(pc.size) >> level);
  return bilinearBlend(b, texelFetch(s, ivec3(b.i0, layer), level),
                       texelFetch(s, ivec3(b.i1.x, b.i0.y, layer), level),
                       texelFetch(s, ivec3(b.i0.x, b.i1.y, layer), level),
                       texelFetch(s, ivec3(b.i1, layer), level));
}

vec4 trilinear(sampler2DArray s, vec2 x, int layer, float level) {
  int l0, l1;
  float upper;
  trilinearLevels(level, int(pc.topLevel), l0, l1, upper);
  return mix(bilinear(s, x, layer, l0), bilinear(s, x, layer, l1), upper);
}

float gMassTop = 1.0;  // fisKernelMass's normalisation: the two layers' top means of m_t

// The fraction of the whole PDF mass in a level-l kernel at x of gLayer: 4^l f~(x, l) /
// (M m_top), f~ the kernel's mean of f_t lum (its directions' mass, those beyond the rim
// included), m_top = the sum of the two layers' top means of m_t (M m_top = the total mass).
float fisKernelMass(vec2 x, float level) {
  float m = float(pc.size) * float(pc.size);
  return exp2(2.0 * level) * trilinear(directionPyramid, x, gLayer, level).w / (gMassTop * m);
}

float modifiedFisLevel(vec2 x, int layer, float massTop) {
  if (!(massTop > 0.0)) return float(pc.topLevel);  // a black environment
  gLayer = layer;
  gMassTop = massTop;
  return modifiedFisBisection(x, pc.kernelScale / float(pc.count), float(pc.topLevel),
                              pc.kernelScale < float(pc.count));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  int topLevel = int(pc.topLevel);
  vec2 u = fibonacciPoint(i, pc.count);
  // The two layers' masses (top means).
  float mass0 = texelFetch(radiancePyramid, ivec3(0, 0, 0), topLevel).a;
  float mass1 = texelFetch(radiancePyramid, ivec3(0, 0, 1), topLevel).a;
  float massTop = mass0 + mass1;
  gLayer = int(split(u.x, mass0, mass1));
  int layer = gLayer;
  ivec2 node = warpToTexel(u, topLevel);
  float size = float(pc.size);
  vec2 x = min((vec2(node) + u) / size, (vec2(node) + kOneBelow) / size);
  float level = modifiedFisLevel(x, layer, massTop);
  vec4 radiance = trilinear(radiancePyramid, x, layer, level);    // (f L, w lum) kernel means
  vec4 direction = trilinear(directionPyramid, x, layer, level);  // (lum dir, f lum)
  float m = size * size;
  EnvSgLight light;
  light.axisSharpness = vec4(0.0, 0.0, 1.0, 0.0);
  light.amplitude = vec4(0.0);
  light.kernel = vec4(x, level, float(layer));
  if (massTop > 0.0 && radiance.a > 0.0 && direction.w > 0.0) {
    // The axis: the sample's own direction (the lattice and the warp distribute it by the
    // PDF; the kernel's mean direction would lean toward the layer's pole). The sharpness:
    // Banerjee's, from the kernel's luminance-weighted mean direction (its spread).
    vec3 meanAxis;
    float sharpness;
    lobeFromMeanAxis(direction.xyz / direction.w, meanAxis, sharpness);
    vec3 axis = envParaboloidDirection(x, uint(layer));
    // Phi = (total mass / N) rgb~ / f~: the kernel's radiance per unit luminance, times the
    // light's equal share of the mass; then the staircase rim's solid angle rescaled to 4 pi.
    vec3 phi = (m * massTop / float(pc.count)) * (radiance.rgb / direction.w);
    light.axisSharpness = vec4(axis, sharpness);
    light.amplitude = vec4(phi * (pc.solidAngleScale / sgIntegral(sharpness)),
                           2.0 * radiance.a / massTop);
  }
  lights[i] = light;
}
