// The view-dependent PDF over RSM texels (bidirectional RSM, vsgl-math.md section 7), stage B:
// the camera's importance VSGLs (stage A: the camera G-buffer through the flux, attribute and
// generation passes) "light" the RSM, and a texel's PDF is the importance its VPL reflects.
//
// brsm_evaluate.comp runs on a grid of cells, the RSM pyramids' level log2(size / gridSize)
// (one cell = one texel when the grid is the RSM's size), bound as that level's views. Each cell is
// a VPL cluster: its flux-weighted mean position and the diffuse and glossy vMF lobes that the
// generation pass would build from the same sums (sections 3.2-3.3). The importance a lobe c
// reflects per unit power is
//   I_c = sum over importance lobes k of  integral W_k(w) vMF_c(w) dw,
// W_k the importance VSGL's incoming SG at the cell (section 4.1) and vMF_c the cell lobe
// normalised to integrate to 1: by reciprocity the image contribution of power Phi leaving
// with that distribution. Cell output (RGBA32F, a pyramid so that its top is the mean):
//   r = I_d, g = I_s, b = I_d w_d + I_s w_s (the cell's mean of the BRSM term), a = 0,
// w_d, w_s the cell's mean diffuse and glossy weights (luminance of power).
//
// brsm_compose.comp writes the PDF channel (alpha of VSGL_ATTR_DIFFUSE_AXIS) at level 0:
//   p(t) = (1 - e) (I_d w_d(t) + I_s w_s(t)) / mean_B + e (w_d(t) + w_s(t)) / mean_w,
// I of the texel's cell, e = fluxMix > 0 so that no lit texel has p = 0, both terms of mean 1.
// Without any importance (mean_B = 0: the camera sees nothing lit) p is the flux PDF.
#ifndef SHADERS_SHARED_BRSM_H
#define SHADERS_SHARED_BRSM_H
#include "interop.h"

#define BRSM_GROUP_X 8
#define BRSM_GROUP_Y 8
// Importance lobes whose contribution exceeds this are clamped: a receiver exactly at a
// zero-variance lobe's mean is a point singularity (section 12, case 12), and the clamp keeps
// the PDF and its mips (means, never sums) finite in fp32.
#define BRSM_MAX_IMPORTANCE 1e24

SHARED_BEGIN

struct BrsmEvaluatePush {
  vec4 origin;           // xyz = RSM origin (world): cell positions are stored relative to it
  uint importanceCount;  // importance VSGLs in the buffer
  uint gridSize;         // cells per side (a power of two <= the pyramids' size)
  uint pad0;
  uint pad1;
};

struct BrsmComposePush {
  uint size;      // pyramid base texels per side
  uint shift;     // log2(size / gridSize): texel >> shift = cell
  float fluxMix;  // e in (0, 1]
  uint pad;
};

SHARED_END

SHARED_ASSERT_SIZE(BrsmEvaluatePush, 32);
SHARED_ASSERT_SIZE(BrsmComposePush, 16);
#endif
