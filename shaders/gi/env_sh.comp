#version 460
// Environment SH projection (docs/techniques/environment.md, pass 2): the 9 SH radiance
// coefficients of one level of the dual-paraboloid map, as ONE work group that reduces in
// shared memory. Every texel counts at the direction of its centre with the solid angle of its
// part in its layer's own hemisphere (rho^2 <= 1 in layer 0, < 1 in layer 1): the midpoint rule
// on ENV_SH_TEXEL_SAMPLES^2 points of the texel, r = 16 b^2 / (1 + rho^2)^2 at each
// (gi/src/reference/env_paraboloid.h). CPU twin: envMapSh and envMapTexelSolidAngle in
// gi/src/reference/env_map_reference.cpp; basis of gi/src/reference/sh_irradiance.h.
#extension GL_GOOGLE_include_directive : require

#include "shared/environment.h"
#include "shared/env_map.h"
#include "common/env_paraboloid.glsl"

layout(local_size_x = ENV_SH_GROUP_SIZE) in;

layout(binding = 0, rgba32f) uniform readonly image2DArray map;  // the projected level
layout(binding = 1, std430) writeonly buffer Coefficients { EnvSh sh; };
layout(push_constant) uniform Push { EnvShPush pc; };

const float kPi = 3.14159265358979;
const int kTerms = 3 * ENV_SH_COEFFICIENTS;

shared float partial[kTerms][ENV_SH_GROUP_SIZE];

// Real SH up to l = 2 without the Condon-Shortley phase, index l (l + 1) + m ([RH01] Eq. 3).
void shBasis(vec3 d, out float y[ENV_SH_COEFFICIENTS]) {
  const float c0 = 0.28209479177;   // 1/2 sqrt(1/pi)
  const float c1 = 0.48860251190;   // sqrt(3 / (4 pi))
  const float c2 = 1.09254843059;   // 1/2 sqrt(15/pi)
  const float c20 = 0.31539156525;  // 1/4 sqrt(5/pi)
  const float c22 = 0.54627421529;  // 1/4 sqrt(15/pi)
  y[0] = c0;
  y[1] = c1 * d.y;
  y[2] = c1 * d.z;
  y[3] = c1 * d.x;
  y[4] = c2 * d.x * d.y;
  y[5] = c2 * d.y * d.z;
  y[6] = c20 * (3.0 * d.z * d.z - 1.0);
  y[7] = c2 * d.x * d.z;
  y[8] = c22 * (d.x * d.x - d.y * d.y);
}

void main() {
  uint tid = gl_LocalInvocationIndex;
  uint n = pc.levelSize;
  float sums[kTerms];
  for (int k = 0; k < kTerms; ++k) sums[k] = 0.0;
  float invN = 1.0 / float(n);  // exact: n is a power of two
  const uint K = ENV_SH_TEXEL_SAMPLES;
  float invKn = 1.0 / float(K * n);  // exact
  uint count = 2u * n * n;
  for (uint index = tid; index < count; index += ENV_SH_GROUP_SIZE) {
    uint layer = index / (n * n);
    uint x = index % n, y = (index / n) % n;
    // The points (x + (i + 1/2) / K, y + (j + 1/2) / K) / n: 2 st - 1 = (2 (K x + i) + 1 - K n)
    // / (K n) exactly, and dot() of two such squares is exact in fp32 (odd numbers < 2^10), so
    // rho^2 carries one rounding; it never ties 1 for K n a power of two (see the twin).
    float solidAngle = 0.0;
    for (uint j = 0u; j < K; ++j)
      for (uint i = 0u; i < K; ++i) {
        vec2 c = vec2(ivec2(2u * (K * uvec2(x, y) + uvec2(i, j)) + 1u) - int(K * n)) * invKn;
        float rho2 = kEnvParaboloidScale * kEnvParaboloidScale * dot(c, c);
        if (layer == 0u ? rho2 > 1.0 : rho2 >= 1.0) continue;
        float onePlusRho2 = 1.0 + rho2;
        solidAngle += 16.0 * kEnvParaboloidScale * kEnvParaboloidScale /
                      (onePlusRho2 * onePlusRho2);
      }
    if (solidAngle == 0.0) continue;
    solidAngle *= invKn * invKn;
    vec2 st = (vec2(x, y) + 0.5) * invN;
    vec3 direction = envParaboloidDirection(st, layer);
    vec3 radiance = imageLoad(map, ivec3(x, y, layer)).rgb * solidAngle;
    float basis[ENV_SH_COEFFICIENTS];
    shBasis(direction, basis);
    for (int i = 0; i < ENV_SH_COEFFICIENTS; ++i)
      for (int ch = 0; ch < 3; ++ch) sums[3 * i + ch] += basis[i] * radiance[ch];
  }
  for (int k = 0; k < kTerms; ++k) partial[k][tid] = sums[k];
  barrier();
  for (uint stride = ENV_SH_GROUP_SIZE / 2; stride > 0u; stride /= 2u) {
    if (tid < stride)
      for (int k = 0; k < kTerms; ++k) partial[k][tid] += partial[k][tid + stride];
    barrier();
  }
  if (tid < uint(ENV_SH_COEFFICIENTS))
    sh.coefficients[tid] =
        vec4(partial[3 * tid][0], partial[3 * tid + 1][0], partial[3 * tid + 2][0], 0.0);
}
