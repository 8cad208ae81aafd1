// How well a set of FIS kernels tiles its PDF: the gaps and overlaps that [S3] Fig. 1 shows for
// the [T15] rule and that modified FIS ([S3] Eq. 3) reduces. A diagnostic for tests and the
// vsgl_kernels sample, not part of generation.
//
// Definition (texel space of level 0, texel (i, j) spans [i, i + 1) x [j, j + 1), its centre at
// (i + 1/2, j + 1/2)): a kernel with centre x in [0, 1]^2 and level l is the axis-aligned square
// of side s = 2^l texels centred at c = x * size, the footprint of one level-l texel that the
// kernel's filtered fetch averages over. It covers texel (i, j) when the texel centre lies in
// [c.x - s/2, c.x + s/2) x [c.y - s/2, c.y + s/2): half-open, so an integer-side kernel covers
// exactly s x s texels (fewer where it leaves the map; texels outside the map do not exist and
// are not counted) whatever the position of its centre. The coverage count of a texel is the
// number of kernels covering it; mass fractions weight each texel by its level-0 PDF value.
// The square is the nominal kernel that [S3] Fig. 1 draws, not the exact weights of the
// trilinear fetch (a tent over neighbouring level-l texels, clamped at the edges): near the top
// level it covers only part of the map unless centred.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "reference/vsgl_sampling.h"

namespace gi {

struct KernelCoverage {
  // Fraction of the PDF's total mass on texels no kernel covers (gaps: that light is lost to
  // the VSGLs whatever their power).
  double uncoveredMass = 0.0;
  // Fraction on texels covered by two or more kernels (overlaps: counted more than once).
  double multiplyCoveredMass = 0.0;
};

// `kernels`: (centre x, centre y, level l) each, as in gpu::Vsgl::kernel.xyz. An all-zero PDF
// has no mass to share out: both fractions are 0.
KernelCoverage measureCoverage(const ScalarPyramid& pdf, const std::vector<glm::dvec3>& kernels);

}  // namespace gi
