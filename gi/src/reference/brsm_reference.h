// CPU twin of BRSM stage B (brsm_evaluate.comp and brsm_compose.comp; formulas in
// shaders/shared/brsm.h and vsgl-math.md section 7), in double with the SG oracle of
// sg_math.h. It takes the light's attribute pyramids as the GPU left them, so the comparison
// isolates stage B.
#pragma once

#include <array>
#include <vector>

#include "reference/vsgl_sampling.h"

namespace gi {

using AttributePyramids = std::array<VectorPyramid, VSGL_ATTR_COUNT>;

// The importance per unit power that one cell lobe reflects: the sum over the importance lobes
// of integral W_k(w) vMF(w) dw (incoming SG of section 4.1 times the vMF normalised to 1),
// clamped to BRSM_MAX_IMPORTANCE. `receiver` in world space; `specular` false reads only the
// importance VSGLs' diffuse lobes.
double reflectedImportance(const std::vector<gpu::Vsgl>& importance, glm::dvec3 receiver,
                           const SgLobe& lobe, bool specular = true);

// The gridSize^2 cells (row-major) read at pyramid level log2(size / gridSize):
// (I_d, I_s, I_d w_d + I_s w_s, 0) with w the cell's mean weights; 0 for cells without power.
// `specular` false (no specular lobes anywhere): only the importance VSGLs' diffuse lobes, and
// I_s = 0, as the GPU's variant without specular lobes.
std::vector<glm::dvec4> brsmCellsReference(const AttributePyramids& light, glm::dvec3 origin,
                                           const std::vector<gpu::Vsgl>& importance,
                                           uint32_t gridSize, bool specular = true);

// The level-0 PDF: (1 - e) (I_d w_d + I_s w_s) / mean_B + e (w_d + w_s) / mean_w with the
// cell of each texel; the flux PDF when mean_B = 0; all zero when mean_w = 0.
std::vector<double> brsmPdfReference(const AttributePyramids& light,
                                     const std::vector<glm::dvec4>& cells, uint32_t gridSize,
                                     double fluxMix);

}  // namespace gi
