// CPU twin of VSGL generation (vsgl-math.md sections 3, 5 and 6), in double and naive on purpose:
// the oracle that the filtered-sampling kernel is tested against.
//
// This work is based on:
//   [S3]  Tokuyoshi, "Modified Filtered Importance Sampling for Virtual Spherical Gaussian
//         Lights", Pacific Graphics 2016 short papers (Eqs. 1-5).
//   [T15] Tokuyoshi, "Virtual Spherical Gaussian Lights for Real-time Glossy Indirect
//         Illumination", CGF 34(7), 2015 (its kernel rule, as [S3] restates it).
//   [C05] Clarberg et al., "Wavelet Importance Sampling", SIGGRAPH 2005 (hierarchical warping).
//   [SJ94] Sloan and Joe, lattice methods (the golden-ratio Fibonacci lattice).
//   [B05] Banerjee et al., "Clustering on the Unit Hypersphere using vMF Distributions", JMLR 2005.
//
// Domain and densities: kernel centres x live in [0, 1]^2 of the RSM; every density below is
// the PDF pyramid divided by its top (1x1) mean, i.e. a density with mean 1 over [0, 1]^2, so
// an unnormalised PDF works as is.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "shared/vsgl.h"
#include "shared/vsgl_attributes.h"

namespace gi {

// A square power-of-two mip pyramid: levels[0] = size x size (row-major), levels[l] =
// (size >> l)^2 exact box means, the last level 1x1 (the mean of the whole map).
template <typename T>
struct Pyramid {
  uint32_t size = 0;
  std::vector<std::vector<T>> levels;

  // L = log2(size): the 1x1 level.
  uint32_t topLevel() const { return uint32_t(levels.size() - 1); }
  const T& at(uint32_t level, uint32_t x, uint32_t y) const {
    return levels[level][size_t{y} * (size >> level) + x];
  }
};
using ScalarPyramid = Pyramid<double>;
using VectorPyramid = Pyramid<glm::dvec4>;

ScalarPyramid makeScalarPyramid(const std::vector<double>& base, uint32_t size);
VectorPyramid makeVectorPyramid(const std::vector<glm::dvec4>& base, uint32_t size);

// Point i of the golden-ratio Fibonacci lattice of n points (section 6.1):
//   u_i = ((i + 1/2) / n, frac((i + 1/2) (phi - 1))).
// Both coordinates are offset by 1/2 so that no point lies on u = 0 (or reaches 1): a point on
// the boundary would select a child of vanishing mass in the warp (section 6.2, section 12
// case 4). Every column [j/n, (j+1)/n) holds exactly point j.
glm::dvec2 fibonacciPoint(uint32_t i, uint32_t n);

struct WarpResult {
  glm::dvec2 x{0.0};     // continuous position in [0, 1]^2, inside `texel`
  glm::uvec2 texel{0u};  // level-0 texel that holds x
  double density = 0.0;  // p(x) = P0(texel) / Ptop, mean-1 density (0 for an all-zero PDF)
};

// Hierarchical sample warping [C05] (section 6.2): maps u in [0, 1)^2 to x distributed with
// the piecewise-constant density of levels[0]. Each step is an order-preserving affine rescale
// of one coordinate, so equal areas of u map to equal probability mass and a stratified point
// set stays stratified.
WarpResult warpHierarchical(const ScalarPyramid& pdf, glm::dvec2 u);

// The density that warpHierarchical samples, at x (mean 1; 0 for an all-zero PDF).
double pdfDensity(const ScalarPyramid& pdf, glm::dvec2 x);

// What a Vulkan sampler returns with LINEAR min/mag/mipmap filters and CLAMP_TO_EDGE:
// bilinear at floor(level) and floor(level) + 1 (texel centres at (i + 1/2) / size), blended by
// the fraction; level clamped to [0, L].
template <typename T>
T sampleTrilinear(const Pyramid<T>& pyramid, glm::dvec2 x, double level);
extern template double sampleTrilinear(const Pyramid<double>&, glm::dvec2, double);
extern template glm::dvec4 sampleTrilinear(const Pyramid<glm::dvec4>&, glm::dvec2, double);

// Probability mass of a kernel at level l centred on x, 4^l p~(x, l) / M ([S3] Eq. 3 left side)
// with p~ the trilinear, mean-1 filtered density; it is 1 at l = L and 0 for an all-zero PDF.
double kernelMass(const ScalarPyramid& pdf, glm::dvec2 x, double level);

// [T15] kernel rule ([S3] Eq. 1): 4^l / M = min(K / (N p(x)), 1), i.e.
// l = clamp(log4(K M / (N p)), 0, L) with p the unfiltered mean-1 density at the centre; p = 0
// gives L.
double tok15Level(double pdfDensityAtCentre, uint32_t n, double k, uint32_t size);

// Modified FIS ([S3] Eq. 3 with K / N): the level at which kernelMass = K / N, by bisection on
// [0, L]. Returns 0 when the texel under x already holds that mass, L when K >= N (no smaller
// kernel holds it) or the PDF is all zero; otherwise the midpoint of the final interval, so the
// error is at most L / 2^(steps + 1) levels.
double modifiedFisLevel(const ScalarPyramid& pdf, glm::dvec2 x, uint32_t n, double k,
                        int steps = VSGL_BISECTION_STEPS);

// The factors that turn attribute kernel MEANS (what a mip fetch returns) into cluster SUMS.
// Modified FIS, [S3] Eq. 5: M / (N p~(x, l)) (0 when p~ = 0).
double modifiedFisScale(double filteredDensity, uint32_t n, uint32_t texelCount);
// [T15], [S3] Eq. 4: M / max(N p(x), 1) with the unfiltered centre density p(x).
double tok15Scale(double pdfDensityAtCentre, uint32_t n, uint32_t texelCount);

// Banerjee's vMF concentration estimate from a mean resultant length r ([B05], section 3.3):
// r (3 - r^2) / (1 - r^2); 0 for r <= 0, VSGL_MAX_SHARPNESS for r >= 1 and beyond the clamp.
double banerjeeSharpness(double meanLength);
// Its inverse, the per-VPL vector length that reproduces `sharpness` (section 3.3): the root
// in [0, 1) of r^3 - lambda r^2 - 3 r + lambda by the trigonometric closed form; 1 above 2^25.
double banerjeeMeanLength(double sharpness);

struct SgLobe {
  glm::dvec3 axis{0.0, 0.0, 1.0};  // unit
  double sharpness = 0.0;
};

// The SG reflection lobe of one VPL (section 3.3, "Specular lobe"): GGX with
// alpha = max(roughness^2, 1e-3) (shaders/common/brdf.glsl), lit from unit direction omegaIn
// (VPL -> light) on a surface with unit normal n. Axis = reflect(-omegaIn, h) about the dominant
// visible normal h; sharpness = lambda_h h.n / (4 |omegaIn . h|), lambda_h = 2 / alpha^2 - 2.
SgLobe specularLobe(glm::dvec3 n, glm::dvec3 omegaIn, double roughness);

// The share of a VPL's glossy lobe of `sharpness` that the VSGL's glossy lobe carries, the rest
// joining the diffuse lobe (docs/techniques/vsgl-generation.md, "Broad reflections"): smoothstep
// in log sharpness from VSGL_FLAT_SHARPNESS (0) to VSGL_GLOSSY_SHARPNESS_RATIO times it (1).
double glossyShare(double sharpness);

// Sums of one lobe over a cluster (sections 3.2 and 3.5), in the channel layout of
// shaders/shared/vsgl_attributes.h: power = (Phi rgb, W), position = (P1, P2) relative to the
// RSM origin, axis.xyz = A. Any common scale works for the ratios; `power` is the cluster power.
struct LobeSums {
  glm::dvec4 power{0.0};
  glm::dvec4 position{0.0};
  glm::dvec4 axis{0.0};
};

// A VSGL lobe from its cluster sums (sections 3.2 and 3.4): mean = origin + P1 / W, per-axis
// variance max(0, P2 / W - |P1 / W|^2) / 2, axis and Banerjee sharpness from A / W. W = 0
// gives zero power, zero variance, sharpness 0, axis (0, 0, 1) and mean = origin.
gpu::VsglLobe buildVsglLobe(const LobeSums& sums, glm::dvec3 origin);

// The RSM's texel geometry (RsmView's axis, texelArea and perspective), for VSGL_RULE_POINT.
struct TexelPatch {
  glm::dvec3 axis{0.0, 0.0, -1.0};  // unit direction the light travels
  double texelArea = 0.0;           // spot: on the unit-distance plane; directional: m^2
  bool perspective = true;
};

// The area of the surface patch that one texel covers at offset y from the RSM origin, unit
// normal n: its solid angle from the light (texelArea cos^3 on the unit-distance plane) times
// t^2 / cos at the surface, or a parallel beam's texelArea / cos; cos floored at 1e-6. n = 0
// (no normal known): the patch faces the light.
double texelPatchArea(const TexelPatch& patch, glm::dvec3 offset, glm::dvec3 normal);

// The whole generation pass: for i < n, warp the lattice point, pick the level by `rule`
// (VSGL_RULE_TOK15 or VSGL_RULE_MODIFIED), read the six attribute pyramids (indexed by
// VSGL_ATTR_*) with the same trilinear kernel, scale means to cluster sums with that rule's
// estimator, and build both lobes. kernel = (x, l, p~(x, l)). An all-zero PDF gives n
// zero-power VSGLs. visibilityPoint = origin + the bilinear level-0 position sums over the
// weights at x (w = 1; 0 where x sees no power). VSGL_RULE_POINT (the VPL baseline,
// docs/techniques/vpl-baseline.md): the warped texel alone, at its centre and level 0, over N p;
// both lobes' variance a / (4 pi), the disc of area a = texelPatchArea x max(1, M / (N p)) that the
// VPL stands for. surfaceTolerance > 0 (filtered sampling only): each level is then lowered to
// surfaceLevel's.
std::vector<gpu::Vsgl> generateVsglsReference(
    const std::array<VectorPyramid, VSGL_ATTR_COUNT>& attributes, const ScalarPyramid& pdf,
    glm::dvec3 origin, uint32_t n, double k, uint32_t rule, const TexelPatch& patch = {},
    double surfaceTolerance = 0.0);

// Kernels that leave their surface (docs/techniques/vsgl-generation.md): whether the kernel's
// mean at (x, level), both lobes' weights together, lies more than `tolerance` standard
// deviations (per axis, the lobe variance's) off the plane through `surface` (relative to the
// RSM origin, as the position sums) with the diffuse lobe's mean normal, the offset weighted by
// the kernel's planarity (vsglPlanarity of its diffuse sharpness: a corner is not held to a
// plane); false without diffuse axis or weight.
bool kernelOffSurface(const std::array<VectorPyramid, VSGL_ATTR_COUNT>& attributes, glm::dvec2 x,
                      double level, glm::dvec3 surface, double tolerance);
// The lowest level at which the kernel is off its surface, or `level` if it is not up to there:
// a scan up from 0 in steps of VSGL_SURFACE_SCAN_STEP, then VSGL_SURFACE_BISECTION_STEPS
// bisection steps within the first step that is off (the lower end of the final interval).
double surfaceLevel(const std::array<VectorPyramid, VSGL_ATTR_COUNT>& attributes, glm::dvec2 x,
                    double level, glm::dvec3 surface, double tolerance);

}  // namespace gi
