#version 460
// Environment shading by filtered importance sampling (shaders/shared/env_fis.h; [S1] Colbert
// and Krivanek, GPU Gems 3 ch. 20; [S2] Krivanek and Colbert, EGSR 2008, Section 4): per
// G-buffer pixel,
//   glossy  = (1/N) sum_k w(l_k) Lbar(l_k, level_k),   w = f (n . l) / p,
//   diffuse = albedo / pi * max(E_SH(n), 0),
// l_k from the lobe's sampler at the Hammersley point k of N, Lbar the trilinear read of the
// dual-paraboloid map (shared/environment.h) at the FIS level of the mode. The weights and
// their derivation are in the CPU twin, gi/src/reference/env_fis_reference.{h,cpp}, which this
// shader follows step by step in fp32.
#extension GL_GOOGLE_include_directive : require

#include "shared/environment.h"
#include "shared/env_fis.h"
#include "common/brdf.glsl"
#include "common/camera_ray.glsl"
#include "common/env_paraboloid.glsl"
#include "common/finite_material.glsl"
#include "common/octahedral.glsl"

layout(local_size_x = ENV_FIS_GROUP_X, local_size_y = ENV_FIS_GROUP_Y) in;

layout(binding = 0, r32f) uniform readonly image2D gDepth;
layout(binding = 1, rg16_snorm) uniform readonly image2D gNormal;
layout(binding = 2, rgba16f) uniform readonly image2D gDiffuse;
layout(binding = 3, rgba16f) uniform readonly image2D gSpecular;
// Trilinear, clamp-to-edge; layer 0: z >= 0, layer 1: z < 0.
layout(binding = 4) uniform sampler2DArray envMap;
layout(std430, binding = 5) readonly buffer Sh { EnvSh sh; };
layout(binding = 6, rgba32f) uniform writeonly image2D outDiffuse;
layout(binding = 7, rgba32f) uniform writeonly image2D outGlossy;
layout(push_constant) uniform Push { EnvFisPush pc; };
layout(constant_id = 0) const uint kMode = ENV_FIS_FILTERED;
layout(constant_id = 1) const uint kBrdf = ENV_FIS_GGX;

// ---------------------------------------------------------------------------------------------
// Points, hash, frames

// Hammersley point k of N: (k / N, Phi_2(k)), Phi_2 = the 32 bits of k mirrored (2^-32 scale;
// exact in fp32 for k < 2^24, whose mirror has its low 8 bits clear).
vec2 hammersley(uint k, uint count) {
  return vec2(float(k) / float(count), float(bitfieldReverse(k)) * 2.3283064365386963e-10);
}

// Jarzynski and Olano 2020's PCG hash; gi::envFisHash.
uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The pixel's Cranley-Patterson offset on the 2^-24 grid (gi::envFisRotation).
vec2 pixelRotation(uvec2 pixel) {
  uint a = pcgHash(pixel.x + pcgHash(pixel.y));
  uint b = pcgHash(a);
  return vec2(float(a >> 8u), float(b >> 8u)) * 5.9604644775390625e-8;
}

// Duff et al. 2017's branchless basis around a unit axis, as gi::lobeFrame(axis): the sign is
// copysign(1, z), so -0 picks the lower hemisphere as std::copysign does.
void axisFrame(vec3 axis, out vec3 tangent, out vec3 bitangent) {
  float s = (floatBitsToUint(axis.z) >> 31u) != 0u ? -1.0 : 1.0;
  float a = -1.0 / (s + axis.z);
  float b = axis.x * axis.y * a;
  tangent = vec3(1.0 + s * axis.x * axis.x * a, s * b, -s * axis.x);
  bitangent = vec3(b, s + axis.y * axis.y * a, -axis.y);
}

// ---------------------------------------------------------------------------------------------
// Lobe samples: direction l, its pdf [1 / sr] and weight f (n . l) / p (0 below the surface).

struct LobeSample {
  vec3 direction;
  float pdf;
  vec3 weight;
};

struct Receiver {
  vec3 normal;
  vec3 view;
  vec3 f0;
  float f90;
  float alpha;  // GGX alpha, max(r^2, 1e-3)
};

// GGX half-vector sampling: tan^2 theta_h = alpha^2 u1 / (1 - u1), phi = 2 pi u2;
// p(l) = D (n . h) / (4 |v . h|); w = F(v . h) 4 V nl (v . h) / (n . h).
LobeSample sampleGgx(Receiver r, vec2 u) {
  float a2 = r.alpha * r.alpha;
  float tan2 = a2 * u.x / (1.0 - u.x);
  float cosTheta = inversesqrt(1.0 + tan2);
  float sinTheta = sqrt(tan2) * cosTheta;
  float phi = 2.0 * kPi * u.y;
  vec3 hLocal = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
  vec3 t, b;
  axisFrame(r.normal, t, b);
  vec3 h = hLocal.x * t + hLocal.y * b + hLocal.z * r.normal;
  float vh = dot(r.view, h);
  LobeSample s;
  s.direction = 2.0 * vh * h - r.view;
  // D with sin^2 from the local x, y (exact near the pole, as gi::ggxHalfVectorPdf).
  float d = hLocal.z * hLocal.z * a2 + dot(hLocal.xy, hLocal.xy);
  float halfPdf = a2 / (kPi * d * d) * hLocal.z;
  s.pdf = abs(vh) > 0.0 ? halfPdf / (4.0 * abs(vh)) : 0.0;
  s.weight = vec3(0.0);
  float nl = dot(r.normal, s.direction);
  if (nl > 0.0 && vh > 0.0) {
    float nv = max(dot(r.normal, r.view), 1e-4);
    s.weight = schlickFresnel(r.f0, r.f90, vh) *
               (4.0 * smithGgxCorrelatedV(nv, nl, a2) * nl * vh / hLocal.z);
  }
  return s;
}

// Normalised Phong around the mirror 2 (n . v) n - v with e = 2 / alpha^2 - 2:
// cos theta = (1 - u1)^(1 / (e + 1)), pdf = (e + 1) / (2 pi) cos^e = (e + 1) / (2 pi)
// (1 - u1)^(e / (e + 1)) (the u form avoids pow(cos, e) of a cosine rounded to 1); w = F0.
LobeSample samplePhong(Receiver r, vec2 u) {
  float a2 = r.alpha * r.alpha;
  float e = 2.0 / a2 - 2.0;
  vec3 mirror = 2.0 * dot(r.normal, r.view) * r.normal - r.view;
  float cosTheta = pow(1.0 - u.x, 1.0 / (e + 1.0));
  float sinTheta = sqrt(max((1.0 - cosTheta) * (1.0 + cosTheta), 0.0));
  float phi = 2.0 * kPi * u.y;
  vec3 t, b;
  axisFrame(mirror, t, b);
  LobeSample s;
  s.direction = sinTheta * cos(phi) * t + sinTheta * sin(phi) * b + cosTheta * mirror;
  s.pdf = (e + 1.0) / (2.0 * kPi) * pow(1.0 - u.x, e / (e + 1.0));
  s.weight = dot(r.normal, s.direction) > 0.0 ? r.f0 : vec3(0.0);
  return s;
}

// Anisotropic Ward (Walter 2005) in the frame (tangent, normal x tangent, normal), alpha_x =
// alpha, alpha_y = alpha * ratio: phi_h = atan2(ay sin 2 pi u2, ax cos 2 pi u2),
// tan^2 theta_h = -ln(1 - u1) / A(phi_h), p(h) = exp(-tan^2 A) / (pi ax ay cos^3) = (1 - u1) /
// (pi ax ay cos^3), p(l) = p(h) / (4 |v . h|); w = F0.
LobeSample sampleWard(Receiver r, vec2 u) {
  float ax = r.alpha, ay = r.alpha * pc.wardAnisotropy;
  // gi::envFisTangent, then Gram-Schmidt as gi::lobeFrame(normal, hint).
  vec3 axis = abs(r.normal.y) > 0.999 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 hint = normalize(cross(axis, r.normal));
  vec3 t = normalize(hint - dot(hint, r.normal) * r.normal);
  vec3 b = cross(r.normal, t);
  float psi = 2.0 * kPi * u.y;
  float phi = atan(ay * sin(psi), ax * cos(psi));
  float cosPhi = cos(phi), sinPhi = sin(phi);
  float a = cosPhi * cosPhi / (ax * ax) + sinPhi * sinPhi / (ay * ay);
  float tan2 = -log(1.0 - u.x) / a;
  float cosTheta = inversesqrt(1.0 + tan2);
  float sinTheta = sqrt(tan2) * cosTheta;
  vec3 h = sinTheta * cosPhi * t + sinTheta * sinPhi * b + cosTheta * r.normal;
  float vh = abs(dot(r.view, h));
  LobeSample s;
  s.direction = 2.0 * dot(r.view, h) * h - r.view;
  float halfPdf = (1.0 - u.x) / (kPi * ax * ay * cosTheta * cosTheta * cosTheta);
  s.pdf = vh > 0.0 ? halfPdf / (4.0 * vh) : 0.0;
  s.weight = dot(r.normal, s.direction) > 0.0 && s.pdf > 0.0 ? r.f0 : vec3(0.0);
  return s;
}

LobeSample sampleLobe(Receiver r, vec2 u) {
  if (kBrdf == ENV_FIS_PHONG) return samplePhong(r, u);
  if (kBrdf == ENV_FIS_WARD) return sampleWard(r, u);
  return sampleGgx(r, u);
}

// ---------------------------------------------------------------------------------------------
// The map and the SH irradiance

// [S2] Section 4: l = max(log4(K S^2 / (N p r)), 0), r = 4 b^2 (1 + |z|)^2 (one S x S layer is
// the map whose Jacobian r is); clamped to the coarsest level (p = 0 gives +inf).
float fisLevel(float pdf, vec3 direction) {
  float r = envParaboloidSolidAnglePerArea(direction);
  float size = float(pc.mapSize);
  float texels = pc.kernelExtent * size * size / (float(pc.sampleCount) * pdf * r);
  return min(max(0.5 * log2(texels), 0.0), float(pc.levelCount - 1u));
}

vec3 envLookup(vec3 direction, float level) {
  vec2 st = envParaboloidCoordinates(direction);
  return textureLod(envMap, vec3(st, float(envParaboloidLayer(direction))), level).rgb;
}

// E(n) = sum_l A_l sum_m L_lm Y_lm(n) (Ramamoorthi and Hanrahan 2001, Eq. 8; basis and order
// of gi/src/reference/sh_irradiance.h): A = pi, 2 pi / 3, pi / 4.
vec3 shIrradiance(vec3 n) {
  const float c0 = 0.28209479177387814;   // 1/2 sqrt(1 / pi)
  const float c1 = 0.4886025119029199;    // sqrt(3 / (4 pi))
  const float c2 = 1.0925484305920792;    // 1/2 sqrt(15 / pi)
  const float c20 = 0.31539156525252005;  // 1/4 sqrt(5 / pi)
  const float c22 = 0.5462742152960396;   // 1/4 sqrt(15 / pi)
  const float a0 = kPi, a1 = 2.0 * kPi / 3.0, a2 = kPi / 4.0;
  vec3 e = a0 * c0 * sh.coefficients[0].rgb;
  e += a1 * c1 * (n.y * sh.coefficients[1].rgb + n.z * sh.coefficients[2].rgb +
                  n.x * sh.coefficients[3].rgb);
  e += a2 * (c2 * n.x * n.y * sh.coefficients[4].rgb + c2 * n.y * n.z * sh.coefficients[5].rgb +
             c20 * (3.0 * n.z * n.z - 1.0) * sh.coefficients[6].rgb +
             c2 * n.x * n.z * sh.coefficients[7].rgb +
             c22 * (n.x * n.x - n.y * n.y) * sh.coefficients[8].rgb);
  return e;
}

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
  // Non-finite material channels read as 0 (albedo, F0, F90) or 1 (roughness).
  vec4 diffuseRoughness = finiteOr(imageLoad(gDiffuse, coord), vec4(0.0, 0.0, 0.0, 1.0));
  vec4 specular = finiteOr(imageLoad(gSpecular, coord), vec4(0.0));
  Receiver r;
  r.normal = octDecode(imageLoad(gNormal, coord).rg);
  r.view = -direction;
  r.f0 = specular.rgb;
  r.f90 = specular.a;
  r.alpha = max(diffuseRoughness.a * diffuseRoughness.a, kMinAlpha);

  vec2 offset = kMode == ENV_FIS_RANDOMISED ? pixelRotation(pixel) : vec2(0.0);
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < pc.sampleCount; ++k) {
    vec2 u = hammersley(k, pc.sampleCount);
    if (kMode == ENV_FIS_RANDOMISED) u = fract(u + offset);
    LobeSample s = sampleLobe(r, u);
    if (s.weight == vec3(0.0)) continue;
    float level = kMode == ENV_FIS_FILTERED ? fisLevel(s.pdf, s.direction) : 0.0;
    sum += s.weight * envLookup(s.direction, level);
  }
  vec3 diffuse = diffuseRoughness.rgb / kPi * max(shIrradiance(r.normal), vec3(0.0));
  imageStore(outDiffuse, coord, vec4(diffuse, 1.0));
  imageStore(outGlossy, coord, vec4(sum / float(pc.sampleCount), 1.0));
}
