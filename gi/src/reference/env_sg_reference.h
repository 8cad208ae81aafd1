// The CPU twin of the environment's SG lights (docs/techniques/environment.md, pass 4;
// shaders/gi/env_sg_pyramid.comp, env_sg_generate.comp, env_sg_shade.comp, host
// gi/src/passes/env_sg.h): the attribute pyramids of the converted map, N SG lights by
// modified filtered importance sampling on the map's luminance x solid-angle PDF, and the
// shading of a receiver with them. Double, naive on purpose; the same lattice, warp, bisection
// and trilinear reads as the shader, so that tests/gpu/test_env_sg.cpp can hold the GPU to it.
//
// This work is based on:
//   [S3]  Tokuyoshi, "Modified Filtered Importance Sampling for Virtual Spherical Gaussian
//         Lights", Pacific Graphics 2016 short papers (Eq. 2: a kernel per stratum of mass 1/N;
//         Eq. 3: its mip level from the PDF pyramid; Eq. 5: the cluster value f~ / (N p~)).
//   [C05] Clarberg et al., "Wavelet Importance Sampling", SIGGRAPH 2005 (hierarchical warping).
//   [SJ94] Sloan and Joe (the golden-ratio Fibonacci lattice).
//   [B05] Banerjee et al., JMLR 2005 (vMF sharpness from a mean resultant length).
//   [T24] Tokuyoshi et al. 2024 (SG x clamped cosine; SG x GGX via gi/src/reference/sg_math.h).
//
// The PDF. Texel t (both layers, 2 M texels, M = S^2 per layer) has w_t = the solid angle of its
// part in its layer's own hemisphere (envMapTexelSolidAngle's midpoint rule; 0 outside the disc,
// partial on the rim), radiance L_t (the map's level 0) and mass m_t = w_t lum(L_t), lum the
// Rec.709 luminance. Directions are drawn with probability p_t = m_t / sum m: a 2-way split of
// the lattice point's u_x between the layers by their masses, then [C05]'s quadtree warp of the
// chosen layer. Both are order-preserving affine rescales, so the N lattice points stay
// stratified: each owns ~1/N of the mass.
//
// Two weights per texel: w_t (own hemisphere only: the PDF, so that every direction is drawn
// once) and f_t = the texel's whole solid angle (outside the disc the texel holds REAL
// directions of the other hemisphere, [S1]'s reason for b = 1.2), used by the kernels so that a
// kernel near the rim sees the directions on both sides of the equator (up to the square's
// edge), not just its own side.
//
// The kernel ([S3] Eq. 3 with K). The pyramids hold per-texel means, so a trilinear read at
// level l is sum_t k_t F_t with kernel weights k_t summing to 1 and spanning ~4^l texels. Its
// mass fraction is g(l) = 4^l f~(x, l) / (M m_top), f~ the kernel mean of f_t lum(L_t) (the mass
// of the directions under it) and m_top the sum of the two layers' top means of m_t
// (M m_top = sum m). g grows with l; the level is the root of g(l) = K / N by bisection
// (VSGL_BISECTION_STEPS steps, midpoint of the last interval); 0 when the texel alone holds
// K / N (a spike: several lights share it), L when K >= N (or when g(L) < K / N).
//
// The estimator. Light i stands for a 1/N share of the luminance mass and for the kernel's
// radiance per unit luminance ([S3] Eq. 5 with the mass fixed at 1/N):
//     Phi_i = (sum m / N) rgb~ / f~,   rgb~ = sum_t k_t f_t L_t,  f~ = sum_t k_t f_t lum(L_t),
// so lum Phi_i = sum m / N exactly. For a one-texel kernel this is the importance-sampling
// estimator f_t / (N p_t) of I = sum_t w_t L_t with p_t = m_t / sum m: E[sum_i Phi_i] =
// sum_t p_t N w_t L_t / (N p_t) = I, unbiased. For a wider kernel it is the kernel's ratio
// estimator: unbiased wherever the chromaticity L / lum(L) is constant over the kernel, and
// exact, light by light, for a constant environment: Phi_i = (sum w) L / N, sum_i Phi_i =
// (sum w) L. The midpoint rule's staircase rim makes sum w differ from 4 pi (by < 1e-4); every
// Phi is scaled by 4 pi / sum w (envSgOwnSolidAngle; the GPU gets it as a push constant), so a
// constant environment integrates to 4 pi L exactly (to rounding). The density p~ = m~ / m_bar
// (m_bar = m_top / 2, the mean over the 2 M texels) of [S3]'s f~ / (N p~) is stored for tests.
//
// The fit. The axis is the sample's own direction, paraboloidToDirection(x, layer): the lattice
// and the warp distribute it by the PDF. The sharpness comes from the luminance-weighted mean
// direction of the kernel, a = d~ / f~ with d~ = sum_t k_t lum(L_t) integral over texel t of
// w dw (the pyramid keeps the INTEGRAL of the direction, not f_t times the centre's direction,
// so a single texel has |a| < 1 by its own angular extent): Banerjee's kappa(|a|)
// (lobeFromMeanAxis; vMF concentration in R^3), the kernel's spread. The amplitude makes the
// SG's integral over the sphere the light's share: amplitude = Phi_i (4 pi / sum w) /
// S(sharpness), S = sgIntegral. A black kernel or environment gives a zero light (axis +z,
// sharpness 0). Why not the mean direction as the axis (the VSGLs' choice): a kernel is a
// square in texture space whose solid angle grows toward its layer's pole, so the mean lies
// poleward of the sample (~0.06 in z at N = 64, K = 1). Measured on a constant environment
// (tests/unit/test_env_sg_reference.cpp, ConstantEnvironmentIsExact), worst diffuse error at
// N = 64: 7.5 % with the mean axis, 1.6 % with the sample's.
//
// The shading of a receiver (normal n, view v, albedo, GGX material), no visibility:
//   diffuse = albedo sum_i amplitude_i D(lambda_i, axis_i . n)   (D =
//   sgClampedCosineIntegralOverPi) glossy  = sum_i amplitude_i sgGgxReflection(SG_i, receiver)
//   (unit-amplitude SG)
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "reference/env_fis_reference.h"
#include "reference/env_map_reference.h"
#include "reference/vsgl_sampling.h"
#include "shared/env_sg.h"
#include "shared/vsgl.h"

namespace gi {

// Rec.709 luminance of linear RGB: 0.2126 r + 0.7152 g + 0.0722 b.
double envSgLuminance(glm::dvec3 rgb);

// Texel (x, y) of an n x n level of `layer`: the solid angle w of its part in the layer's own
// hemisphere and the integral of the unit direction over that part, both by the midpoint rule
// on K x K points, K = ENV_SG_TEXEL_SAMPLES (solidAngle equals envMapTexelSolidAngle).
struct EnvSgTexelWeight {
  double solidAngle = 0.0;      // the part in the own hemisphere (envMapTexelSolidAngle)
  double fullSolidAngle = 0.0;  // the whole texel, the other hemisphere's part included
  glm::dvec3 direction{0.0};    // integral of w dw over the whole texel; |.| <= fullSolidAngle
};
EnvSgTexelWeight envSgTexelWeight(uint32_t n, uint32_t layer, uint32_t x, uint32_t y);

// The attribute pyramids of shared/env_sg.h from level 0 of `map`: [which][layer], which =
// ENV_SG_RADIANCE (rgb f L, a w lum) or ENV_SG_DIRECTION (xyz lum * direction integral over the
// whole texel, w f lum),
// levels of exact box means (mipReference).
struct EnvSgPyramids {
  uint32_t size = 0;
  std::array<std::array<VectorPyramid, 2>, ENV_SG_PYRAMIDS> pyramids;
  // The PDF mass (the radiance pyramid's alpha) of each layer as a scalar pyramid, for the warp.
  std::array<ScalarPyramid, 2> mass;

  uint32_t topLevel() const { return pyramids[0][0].topLevel(); }
  // Sum over both layers of the top means: M massTop = sum m (M = size^2).
  double massTop() const;
  // The total own-hemisphere solid angle sum w (~4 pi), envSgOwnSolidAngle(size).
  double solidAngle = 0.0;
};
EnvSgPyramids envSgPyramids(const EnvMapReference& map);

// One light as the generation pass writes it (gpu::EnvSgLight), in double.
struct EnvSgLightReference {
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double sharpness = 0.0;
  glm::dvec3 amplitude{0.0};
  double density = 0.0;  // p~ = m~ / m_bar: the kernel's PDF density relative to the mean
  glm::dvec2 x{0.5};     // the kernel centre (s, t) in its layer
  double level = 0.0;    // the kernel's mip level
  uint32_t layer = 0;
  uint32_t texel[2] = {0, 0};  // the level-0 texel the warp chose

  // The SG's integral over the sphere, amplitude S(sharpness) (rgb).
  glm::dvec3 integral() const;
};

// The warp of lattice point u: the layer split, then [C05]'s quadtree of that layer. Returns
// the layer and the warp (position, texel) inside it.
struct EnvSgWarp {
  uint32_t layer = 0;
  WarpResult warp;
};
EnvSgWarp envSgWarp(const EnvSgPyramids& pyramids, glm::dvec2 u);

// The fraction of the total PDF mass in the level-l kernel at x of `layer`:
// 4^l m~(x, l) / (M m_top) (the layer's share of the mass at l = L; 0 for a black environment).
double envSgKernelMass(const EnvSgPyramids& pyramids, uint32_t layer, glm::dvec2 x, double level);
// The level at which envSgKernelMass = K / N (file comment), by `steps` bisection steps.
double envSgKernelLevel(const EnvSgPyramids& pyramids, uint32_t layer, glm::dvec2 x, uint32_t n,
                        double k, int steps = VSGL_BISECTION_STEPS);

// N lights, kernels of mass K / N (K in [1, N]), as env_sg_generate.comp.
std::vector<EnvSgLightReference> generateEnvSgLightsReference(const EnvSgPyramids& pyramids,
                                                              uint32_t n, double k = 1.0);

// A receiver shaded with the lights (file comment): GGX with alpha = envFisGgxAlpha(roughness),
// f0, f90; receiver.brdf is ignored (always GGX, as the G-buffer).
EnvShading envSgShade(const EnvFisReceiver& receiver,
                      const std::vector<EnvSgLightReference>& lights);

}  // namespace gi
