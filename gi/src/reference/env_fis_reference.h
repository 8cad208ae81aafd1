// The CPU twin of shaders/gi/env_fis.comp (docs/techniques/environment.md, pass 3): environment
// lighting of one receiver by filtered importance sampling (FIS), and a converged Monte Carlo
// reference of the same receiver against the true radiance function. Double, naive on purpose.
//
// This work is based on:
//   [S1] Colbert and Krivanek, "GPU-Based Importance Sampling", GPU Gems 3 ch. 20, 2007 (the
//        estimator (1/N) sum f cos / p L(l_i), Hammersley points, the lobe-proportional pdf
//        whose weights reduce to the reflectance).
//   [S2] Krivanek and Colbert, "Real-time Shading with Filtered Importance Sampling", EGSR 2008
//        (Section 4: each sample reads the pre-filtered map at l = max(log4(K S^2 / (N p r)),
//        0), K = 4).
//   [CP76] Cranley and Patterson, "Randomization of Number Theoretic Methods for Multiple
//        Integration", SIAM J. Numer. Anal. 13(6), 1976 (the rotation u -> frac(u + offset)).
//   [JO20] Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020 (the PCG
//        hash of the per-pixel offset).
//
// The estimator. For a receiver with normal n and view v (unit, toward the viewer),
//   L_glossy ~ (1/N) sum_k w(l_k) Lbar(l_k, level_k),   w = f(l, v) (n . l) / p(l),
// l_k drawn from the lobe's sampler (env_sampling.h) at the Hammersley point k of N, and
//   L_diffuse = albedo / pi * max(E(n), 0),  E = shIrradiance(sh, n) (sh_irradiance.h; the
// clamp removes the negative ringing of nine terms opposite a bright, small source).
// Samples below the surface (n . l <= 0) weigh 0; they still count in the 1/N.
//
// Weights (this file's derivation; tests/unit/test_env_fis_reference.cpp checks the GGX one
// against engine::ggxSpecular / ggxPdf):
//   GGX (common/brdf.glsl): f = D V F with V = G2 / (4 nl nv) the height-correlated Smith term
//     smithGgxCorrelatedV and F = Schlick(F0, F90, v . h); the half-vector sampler has
//     p(l) = D (n . h) / (4 v . h). D cancels:
//         w = F(v . h) 4 V(nv, nl, alpha^2) nl (v . h) / (n . h)
//           = F(v . h) G2 (v . h) / (nv (n . h)),
//     with brdf.glsl's floors (alpha = max(r^2, 1e-3), nv = max(n . v, 1e-4)); w = 0 when
//     nl <= 0 or v . h <= 0 (brdf.glsl's h = normalize(v + l) is then -h, whose D is 0).
//   Phong and Ward: the glossy lobe IS the sampler's normalised density times a constant
//     reflectance, f(l, v) (n . l) = F0 pdf(l) for n . l > 0 (no Fresnel, no shadowing; F90 is
//     unused), so w = F0 on every sample above the surface. The lobe loses the part of its
//     density that falls below the horizon; a constant environment L gives
//     F0 L P(n . l > 0) <= F0 L.
//     Phong: pdf = (e + 1) / (2 pi) cos^e(mirror, l) around the mirror direction
//       2 (n . v) n - v ([S1]'s lobe). Ward: pdf = p(h) / (4 |v . h|) of the anisotropic Ward
//       half-vector density in the frame (tangent, bitangent, n) ([W05] in env_sampling.h).
//
// Modes: Filtered reads every sample at the level rule, Unfiltered at level 0, Randomised at
// level 0 with the Hammersley set rotated by the pixel's offset envFisRotation ([CP76]).
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>

#include "reference/env_map_reference.h"
#include "reference/env_sampling.h"
#include "reference/sh_irradiance.h"

namespace gi {

// ---------------------------------------------------------------------------------------------
// The map as the GPU samples it

// Bilinear read of one level of one layer, as a Vulkan LINEAR / CLAMP_TO_EDGE sampler filters:
// texel centres at (i + 1/2) / n, st * n - 1/2 split into a texel and a fraction, the texel
// indices clamped to [0, n - 1]. `st` may lie anywhere.
glm::dvec3 envMapBilinear(const EnvMapReference& map, uint32_t layer, glm::dvec2 st,
                          uint32_t level);
// Trilinear read (mipmapMode LINEAR): `level` clamped to [0, levels - 1], then the bilinear
// reads of floor(level) and floor(level) + 1 (clamped) mixed by the fraction.
glm::dvec3 envMapTrilinear(const EnvMapReference& map, uint32_t layer, glm::dvec2 st, double level);
// The map at a unit direction: its layer (z >= 0: 0) and paraboloid coordinates
// (env_paraboloid.h), read trilinearly at `level`.
glm::dvec3 envMapLookup(const EnvMapReference& map, glm::dvec3 direction, double level);
inline uint32_t envMapLevelCount(const EnvMapReference& map) {
  return static_cast<uint32_t>(map.levels.size());
}

// ---------------------------------------------------------------------------------------------
// Receivers and settings

enum class EnvFisMode : uint32_t { Filtered = 0, Unfiltered = 1, Randomised = 2 };  // ENV_FIS_*
enum class EnvFisBrdf : uint32_t { Ggx = 0, Phong = 1, Ward = 2 };

// A receiver without a position (the environment is infinitely far and unshadowed).
struct EnvFisReceiver {
  glm::dvec3 normal{0.0, 0.0, 1.0};  // unit
  glm::dvec3 view{0.0, 0.0, 1.0};    // unit, toward the viewer
  glm::dvec3 albedo{0.0};            // diffuse albedo
  glm::dvec3 f0{0.0};                // GGX: Schlick F0; Phong, Ward: the constant reflectance
  double f90 = 1.0;                  // GGX only: Schlick F90
  EnvFisBrdf brdf = EnvFisBrdf::Ggx;
  double roughness = 1.0;             // GGX: perceptual, alpha = max(r^2, 1e-3) (brdf.glsl)
  double phongExponent = 1.0;         // Phong: e >= 0
  double wardAlphaX = 0.5;            // Ward: roughness along `tangent`, > 0
  double wardAlphaY = 0.5;            // Ward: roughness along normal x tangent, > 0
  glm::dvec3 tangent{1.0, 0.0, 0.0};  // Ward: a hint not parallel to the normal
};

// The G-buffer's material turned into each lobe, as env_fis.comp does: alpha = max(r^2, 1e-3);
// Phong e = 2 / alpha^2 - 2 (the exponent whose lobe matches Beckmann / GGX width alpha);
// Ward alpha_x = alpha, alpha_y = alpha * anisotropy, tangent = envFisTangent(normal).
EnvFisReceiver envFisReceiverFromMaterial(glm::dvec3 normal, glm::dvec3 view, glm::dvec3 albedo,
                                          double roughness, glm::dvec3 f0, double f90,
                                          EnvFisBrdf brdf, double wardAnisotropy = 1.0);
// The Ward tangent of a G-buffer pixel (the G-buffer has none): (0, 1, 0) x normal, or
// (1, 0, 0) x normal where |normal.y| > 0.999, normalised. Continuous away from the poles +-y.
glm::dvec3 envFisTangent(glm::dvec3 normal);

// GGX alpha of a perceptual roughness: max(r^2, 1e-3), brdf.glsl's floor.
double envFisGgxAlpha(double roughness);

// [JO20]'s PCG hash (one round of a 32-bit LCG, then a random xorshift and a multiply).
uint32_t envFisHash(uint32_t v);
// The Randomised mode's Cranley-Patterson offset of a pixel, in [0, 1)^2 on a 2^-24 grid (exact
// in fp32): a = hash(x + hash(y)), b = hash(a), offset = (a >> 8, b >> 8) 2^-24.
glm::dvec2 envFisRotation(glm::uvec2 pixel);

struct EnvFisSettings {
  uint32_t sampleCount = 40;  // N [1, ...]; 40 is the papers' real-time budget
  EnvFisMode mode = EnvFisMode::Filtered;
  double kernelExtent = kFisKernelExtent;  // K of the level rule; 4 = [S1]'s +1 level bias
  glm::uvec2 pixel{0u};                    // Randomised: the pixel whose offset rotates the set
};

// ---------------------------------------------------------------------------------------------
// One lobe sample

struct EnvLobeSample {
  glm::dvec3 direction{0.0, 0.0, 1.0};  // l, unit
  double pdf = 0.0;                     // p(l) [1 / sr] of the lobe's sampler
  glm::dvec3 weight{0.0};               // f (n . l) / p (file comment); 0 below the surface
};
// The sample of u in [0, 1)^2 from the receiver's lobe, with its weight.
EnvLobeSample envFisSampleLobe(const EnvFisReceiver& receiver, glm::dvec2 u);

// ---------------------------------------------------------------------------------------------
// Shading

struct EnvShading {
  glm::dvec3 diffuse{0.0};
  glm::dvec3 glossy{0.0};
};

// The FIS estimate of env_fis.comp: N Hammersley samples of the lobe read from `map` (levels
// by the mode), the diffuse term from `sh`.
EnvShading envFisShade(const EnvFisReceiver& receiver, const EnvMapReference& map, const ShRgb& sh,
                       const EnvFisSettings& settings);

// The Monte Carlo reference against the TRUE environment (a radiance function of direction,
// not the map): the glossy term from glossyStrata^2 jittered-stratified lobe samples (the same
// sampler and weights, so the same integrand), the diffuse term from diffuseStrata^2
// jittered-stratified cosine-weighted samples of albedo L (f cos / p = albedo for Lambert).
// The jitter comes from a fixed-seed LCG (`seed`): the result is deterministic. The standard
// errors are per channel and conservative: the collapsed-strata estimate from pairs of
// neighbouring strata, sqrt(sum (f_a - f_b)^2) / M, which bounds the stratified estimator's
// variance from above (derivation in the .cpp). Odd stratum counts are rounded up to even.
struct EnvReferenceShading {
  EnvShading value;
  glm::dvec3 diffuseStdError{0.0};
  glm::dvec3 glossyStdError{0.0};
};
using EnvRadianceFunction = std::function<glm::dvec3(glm::dvec3)>;
EnvReferenceShading envMonteCarloReference(const EnvFisReceiver& receiver,
                                           const EnvRadianceFunction& radiance,
                                           uint32_t glossyStrata = 128, uint32_t diffuseStrata = 64,
                                           uint64_t seed = 1);

}  // namespace gi
