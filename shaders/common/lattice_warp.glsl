// Stratified, PDF-proportional points over an RSM (vsgl-math.md section 6): the golden-ratio
// Fibonacci lattice warped down a PDF mip pyramid (Clarberg et al. 2005). Shared by the
// filtered-importance kernels and the k-means seeds. The including shader defines
//   float pdfTexel(ivec2 texel, int level)
// before including this file: the PDF at a texel of a pyramid level.
#ifndef SHADERS_COMMON_LATTICE_WARP_GLSL
#define SHADERS_COMMON_LATTICE_WARP_GLSL

const float kOneBelow = 1.0 - 1.0 / 16777216.0;  // largest float below 1

// Golden-ratio Fibonacci lattice with a half-step offset (no point on u = 0). The second
// coordinate frac((i + 1/2)(phi - 1)) is computed in 32-bit fixed point: in fp32 the product
// reaches thousands and its fraction would lose ~1e-4.
vec2 fibonacciPoint(uint i, uint n) {
  const uint kGolden = 2654435769u;  // round((phi - 1) * 2^32)
  uint frac32 = i * kGolden + kGolden / 2u;
  return vec2((float(i) + 0.5) / float(n), float(frac32 >> 8) / 16777216.0);
}

// One binary split of the warp (Clarberg et al. 2005): strict u < q never picks a part of zero
// mass, even for u = 0; a zero parent (all-zero PDF) splits evenly.
uint split(inout float u, float first, float second) {
  float total = first + second;
  float q = total > 0.0 ? first / total : 0.5;
  if (u < q) {
    u = min(u / q, kOneBelow);
    return 0u;
  }
  u = min((u - q) / (1.0 - q), kOneBelow);
  return 1u;
}

// Warps lattice point u down the pyramid from its 1x1 level `topLevel` to the level-0 texel it
// lands in; u is left as the point's position inside that texel, in [0, 1)^2.
ivec2 warpToTexel(inout vec2 u, int topLevel) {
  ivec2 node = ivec2(0);
  for (int level = topLevel; level > 0; --level) {
    int child = level - 1;
    ivec2 c0 = node * 2;
    float a = pdfTexel(c0, child), b = pdfTexel(c0 + ivec2(1, 0), child);
    float c = pdfTexel(c0 + ivec2(0, 1), child), e = pdfTexel(c0 + ivec2(1, 1), child);
    uint column = split(u.x, a + c, b + e);
    uint row = column == 0u ? split(u.y, a, c) : split(u.y, b, e);
    node = c0 + ivec2(column, row);
  }
  return node;
}

#endif
