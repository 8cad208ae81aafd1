// Virtual spherical Gaussian lights (vsgl-math.md sections 3-6): the generation settings and the
// VSGL record that generation writes and shading reads. One record = one kernel of the RSM with
// a diffuse and a glossy lobe, each its own positional Gaussian and SG intensity.
#ifndef SHADERS_SHARED_VSGL_H
#define SHADERS_SHARED_VSGL_H
#include "interop.h"

// Kernel-size rules (vsgl-math.md section 5).
#define VSGL_RULE_TOK15 0u     // l = log4(K M / (N p(x))), estimator f~ / max(N p(x), 1)
#define VSGL_RULE_MODIFIED 1u  // 4^l p~(x, l) / M = K / N by bisection, estimator f~ / (N p~)
// The VPL baseline (docs/techniques/vpl-baseline.md): the level-0 texel under the lattice point,
// estimator f / (N p), both lobes' variance that of the disc the VPL stands for.
#define VSGL_RULE_POINT 2u

// Per-VPL lobe encodings (section 3.3): the diffuse lobe is the vMF fitted to the Lambert pdf,
// sharpness 2.292504, whose Banerjee mean length is this constant.
#define VSGL_DIFFUSE_LOBE_LENGTH 0.5749255543539332
// Planar emitters (docs/techniques/planar-emitters.md): a cluster's planarity is read from its
// diffuse lobe's sharpness, between that of a 90 degree corner (two equal texels at right angles:
// Banerjee's estimate at 0.57492555 / sqrt 2) and that of one texel (Banerjee's estimate at
// VSGL_DIFFUSE_LOBE_LENGTH), where the cluster is flat.
#define VSGL_CORNER_SHARPNESS 1.3805819183117323
#define VSGL_FLAT_SHARPNESS 2.2925040
// Broad reflections join the diffuse lobe (docs/techniques/vsgl-generation.md, "Broad
// reflections"): a VPL's glossy lobe of sharpness at or below the Lambert lobe's
// (VSGL_FLAT_SHARPNESS) is emitted with the diffuse lobe, one at or above this many times it (half
// the Lambert lobe's angular width, 1 / sqrt(lambda)) with the glossy lobe, and one between is
// shared by a smoothstep in log sharpness.
#define VSGL_GLOSSY_SHARPNESS_RATIO 4.0
// Sharpness clamp: Banerjee's estimate diverges as the mean length -> 1 (one VPL, or identical
// axes); 2^41 keeps products with other sharpnesses finite in fp32 (section 12, case 7).
#define VSGL_MAX_SHARPNESS 2199023255552.0
// Modified FIS: bisection iterations on the mip level (the paper's 12).
#define VSGL_BISECTION_STEPS 12
// The search for the level at which a kernel leaves its surface: a scan up from level 0 in steps
// of this many levels, then bisection steps within the first step that leaves (a resolution of
// 0.25 / 2^8 = 0.001 levels).
#define VSGL_SURFACE_SCAN_STEP 0.25
#define VSGL_SURFACE_BISECTION_STEPS 8

SHARED_BEGIN

struct VsglLobe {
  vec4 meanVariance;   // xyz = mean position (world, m), w = per-axis variance v (m^2, >= 0)
  vec4 axisSharpness;  // xyz = unit SG axis, the direction light leaves the VSGL; w = sharpness
  vec4 power;          // rgb = power Phi of the lobe (W), a = scalar weight sum (luminance)
};

struct Vsgl {
  VsglLobe diffuse;
  VsglLobe specular;
  // Filtered sampling: xy = kernel centre in [0, 1]^2 of the RSM, z = mip level l,
  // w = p~(x, l) (mean 1). A k-means cluster (shared/kmeans.h): (0, 0, -1, member texels).
  vec4 kernel;
  // Where the VSGL's imperfect shadow map is rendered from (docs/techniques/ism.md, "The map's
  // centre"): xyz = the lit surface under the kernel's centre (world; the power-weighted mean of
  // the level-0 positions bilinearly around it), w = 1. w = 0 (k-means clusters): the
  // power-weighted mean of the two lobes, which for a kernel spanning two surfaces lies on
  // neither.
  vec4 visibilityPoint;
};

SHARED_END

SHARED_ASSERT_SIZE(VsglLobe, 48);
SHARED_ASSERT_SIZE(Vsgl, 128);
SHARED_ASSERT_OFFSET(Vsgl, kernel, 96);
#endif
