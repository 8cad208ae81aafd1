#include "reference/vsgl_sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

#include "reference/mip_reference.h"
#include "reference/vsgl_emitter.h"

namespace gi {

namespace {

// Largest double below 1 (1 - 2^-53): the double counterpart of the GPU's 1 - 2^-24 clamp.
const double kOneBelow = std::nextafter(1.0, 0.0);
// GGX alpha floor, the same as kMinAlpha in shaders/common/brdf.glsl: alpha^4 stays finite in
// fp32 and the NDF sharpness 2 / alpha^2 stays far below VSGL_MAX_SHARPNESS.
constexpr double kMinAlpha = 1e-3;

double clampUnit(double u) {
  return std::clamp(u, 0.0, kOneBelow);
}

// One binary split of the warp [C05]: chooses `first` with probability first / (first + second)
// and rescales u affinely into [0, 1) inside the chosen part. u < q is strict so a part of zero
// mass (q = 0 or q = 1) is never chosen, not even for u = 0 or u -> 1 (section 12 case 4). A zero
// parent (only an all-zero PDF has one) splits evenly.
uint32_t split(double& u, double first, double second) {
  const double total = first + second;
  const double q = total > 0.0 ? first / total : 0.5;
  if (u < q) {
    u = clampUnit(u / q);
    return 0;
  }
  u = clampUnit((u - q) / (1.0 - q));
  return 1;
}

// Vulkan's LINEAR filter on one level with CLAMP_TO_EDGE: texel centres at (i + 1/2) / size.
template <typename T>
T sampleBilinear(const Pyramid<T>& pyramid, glm::dvec2 x, uint32_t level) {
  const uint32_t n = pyramid.size >> level;
  const glm::dvec2 t = x * double(n) - 0.5;
  const glm::dvec2 base = glm::floor(t);
  const glm::dvec2 f = t - base;
  auto index = [n](double i) { return uint32_t(std::clamp(i, 0.0, double(n - 1))); };
  const uint32_t x0 = index(base.x), x1 = index(base.x + 1.0);
  const uint32_t y0 = index(base.y), y1 = index(base.y + 1.0);
  return (1.0 - f.y) * ((1.0 - f.x) * pyramid.at(level, x0, y0) + f.x * pyramid.at(level, x1, y0)) +
         f.y * ((1.0 - f.x) * pyramid.at(level, x0, y1) + f.x * pyramid.at(level, x1, y1));
}

double topMean(const ScalarPyramid& pdf) {
  return pdf.levels.back()[0];
}

}  // namespace

ScalarPyramid makeScalarPyramid(const std::vector<double>& base, uint32_t size) {
  // Reuse the exact-mean vector pyramid on the first channel.
  std::vector<glm::dvec4> wide(base.size(), glm::dvec4(0.0));
  for (size_t i = 0; i < base.size(); ++i) wide[i].x = base[i];
  ScalarPyramid pyramid{size, {}};
  for (const std::vector<glm::dvec4>& level : mipReference(wide, size)) {
    std::vector<double>& out = pyramid.levels.emplace_back(level.size());
    for (size_t i = 0; i < level.size(); ++i) out[i] = level[i].x;
  }
  return pyramid;
}

VectorPyramid makeVectorPyramid(const std::vector<glm::dvec4>& base, uint32_t size) {
  return {size, mipReference(base, size)};
}

glm::dvec2 fibonacciPoint(uint32_t i, uint32_t n) {
  const double centre = double(i) + 0.5;
  const double v = centre * (std::numbers::phi - 1.0);
  return {centre / double(n), v - std::floor(v)};
}

WarpResult warpHierarchical(const ScalarPyramid& pdf, glm::dvec2 u) {
  u = {clampUnit(u.x), clampUnit(u.y)};
  glm::uvec2 node(0u);
  for (uint32_t level = pdf.topLevel(); level > 0; --level) {
    // Children of `node` one level down: a b in the upper row, c e in the lower one. Column
    // first (mass of a + c against b + e), then the row inside the chosen column.
    const uint32_t child = level - 1, x0 = 2 * node.x, y0 = 2 * node.y;
    const double a = pdf.at(child, x0, y0), b = pdf.at(child, x0 + 1, y0);
    const double c = pdf.at(child, x0, y0 + 1), e = pdf.at(child, x0 + 1, y0 + 1);
    const uint32_t column = split(u.x, a + c, b + e);
    const uint32_t row = column == 0 ? split(u.y, a, c) : split(u.y, b, e);
    node = {x0 + column, y0 + row};
  }
  WarpResult result;
  result.texel = node;
  // node + u rounds up to node + 1 once node >= 1 and u is within an ulp of 1; keep x inside the
  // chosen texel so that pdfDensity(x) and any later texel lookup agree with `density`.
  const double size = pdf.size;
  for (int axis = 0; axis < 2; ++axis)
    result.x[axis] =
        std::min((node[axis] + u[axis]) / size, std::nextafter((node[axis] + 1.0) / size, 0.0));
  const double top = topMean(pdf);
  result.density = top > 0.0 ? pdf.at(0, node.x, node.y) / top : 0.0;
  return result;
}

double pdfDensity(const ScalarPyramid& pdf, glm::dvec2 x) {
  const double top = topMean(pdf);
  if (!(top > 0.0)) return 0.0;
  const double last = pdf.size - 1.0;
  const uint32_t tx = uint32_t(std::clamp(std::floor(x.x * pdf.size), 0.0, last));
  const uint32_t ty = uint32_t(std::clamp(std::floor(x.y * pdf.size), 0.0, last));
  return pdf.at(0, tx, ty) / top;
}

template <typename T>
T sampleTrilinear(const Pyramid<T>& pyramid, glm::dvec2 x, double level) {
  const double top = pyramid.topLevel();
  level = std::clamp(level, 0.0, top);
  const double low = std::floor(level);
  const double fraction = level - low;
  const uint32_t l0 = uint32_t(low), l1 = std::min(l0 + 1, pyramid.topLevel());
  return (1.0 - fraction) * sampleBilinear(pyramid, x, l0) +
         fraction * sampleBilinear(pyramid, x, l1);
}
template double sampleTrilinear(const Pyramid<double>&, glm::dvec2, double);
template glm::dvec4 sampleTrilinear(const Pyramid<glm::dvec4>&, glm::dvec2, double);

double kernelMass(const ScalarPyramid& pdf, glm::dvec2 x, double level) {
  const double top = topMean(pdf);
  if (!(top > 0.0)) return 0.0;
  const double texelCount = double(pdf.size) * pdf.size;
  return std::exp2(2.0 * level) * sampleTrilinear(pdf, x, level) / (top * texelCount);
}

double tok15Level(double pdfDensityAtCentre, uint32_t n, double k, uint32_t size) {
  const double top = std::countr_zero(size);
  if (!(pdfDensityAtCentre > 0.0)) return top;
  const double texelCount = double(size) * size;
  return std::clamp(0.5 * std::log2(k * texelCount / (n * pdfDensityAtCentre)), 0.0, top);
}

double modifiedFisLevel(const ScalarPyramid& pdf, glm::dvec2 x, uint32_t n, double k, int steps) {
  const double top = pdf.topLevel();
  const double target = k / n;
  // All-zero PDF: no kernel holds any mass (section 12 case 1); the caller emits zero power.
  if (!(topMean(pdf) > 0.0)) return top;
  // A spike: the texel under x alone holds K / N, so several VSGLs share it (section 5.3).
  if (kernelMass(pdf, x, 0.0) >= target) return 0.0;
  // kernelMass(L) = 1 < K / N: no kernel is large enough; the whole map / N is still exact.
  if (k >= n) return top;
  // kernelMass grows with l ([S3] after Eq. 2), so [lo, hi] keeps mass(lo) < K / N <= mass(hi).
  double lo = 0.0, hi = top;
  for (int step = 0; step < steps; ++step) {
    const double mid = 0.5 * (lo + hi);
    (kernelMass(pdf, x, mid) < target ? lo : hi) = mid;
  }
  // The midpoint halves the worst-case error of either end: L / 2^(steps + 1).
  return 0.5 * (lo + hi);
}

// The attribute mips hold per-texel MEANS F~ of per-texel quantities F_t (a texel's power, ...),
// and a level-l kernel covers 4^l texels, so its sum is 4^l F~. Equivalently, F as a density on
// [0, 1]^2 is f = M F (a texel has area 1 / M), so [S3]'s f~ is M F~ (section 5.3 units trap).
//
// Modified FIS, [S3] Eq. 5: the kernel holds mass 4^l p~ / M = K / N; the cluster sum
// f~ / (N p~) = M F~ / (N p~) is the kernel sum 4^l F~ rescaled to mass exactly 1 / N, so the
// N clusters share the total whatever the blur (K >= N: M F~_top / N = total / N each).
double modifiedFisScale(double filteredDensity, uint32_t n, uint32_t texelCount) {
  return filteredDensity > 0.0 ? double(texelCount) / (n * filteredDensity) : 0.0;
}

// [T15] as [S3] Eq. 4 restates it (K = 1): the kernel area is a = 4^l / M = min(1 / (N p), 1)
// (Eq. 1) with p the UNFILTERED density at the centre, and the cluster sum is the kernel's
// integral of f, a f~ = M F~ min(1 / (N p), 1) = M F~ / max(N p, 1). For K != 1 the level comes
// from Eq. 1 with K but the divisor stays N p: K only widens the blur, as in Krivanek and
// Colbert's estimator f~ / (N p) (section 5.1), so the N terms still sum to the total on
// average (a literal a f~ with K would make every cluster K / N of the map).
double tok15Scale(double pdfDensityAtCentre, uint32_t n, uint32_t texelCount) {
  return double(texelCount) / std::max(n * pdfDensityAtCentre, 1.0);
}

double banerjeeSharpness(double meanLength) {
  if (!(meanLength > 0.0)) return 0.0;
  if (meanLength >= 1.0) return VSGL_MAX_SHARPNESS;
  // (1 - r)(1 + r): 1 - r is exact near r = 1, 1 - r^2 would lose it.
  const double r = meanLength;
  return std::min(r * (3.0 - r * r) / ((1.0 - r) * (1.0 + r)), VSGL_MAX_SHARPNESS);
}

double banerjeeMeanLength(double sharpness) {
  if (!(sharpness > 0.0)) return 0.0;
  if (sharpness > 0x1p25) return 1.0;
  // Trigonometric root of r^3 - lambda r^2 - 3 r + lambda = 0 (section 3.3, Peters 2016 via [R]).
  const double a = sharpness / 3.0;
  const double phi = std::atan2(std::sqrt(1.0 + 3.0 * a * a * (1.0 + a * a)), a * a * a) / 3.0;
  double r = std::sqrt(1.0 + a * a) * (std::sqrt(3.0) * std::sin(phi) - std::cos(phi)) + a;
  // fp64 only: the closed form cancels two terms of size a, so 1 - r carries an absolute error
  // ~a eps (7e-6 relative at lambda = 1e6, which the sharpness round trip amplifies by
  // 1 / (1 - r)). One Newton step on the cubic, written as lambda (1 - r)(1 + r) + r (r^2 - 3)
  // to keep 1 - r exact, brings r to about an ulp.
  const double f = sharpness * (1.0 - r) * (1.0 + r) + r * (r * r - 3.0);
  const double df = 3.0 * r * r - 2.0 * sharpness * r - 3.0;  // <= -3 on [0, 1)
  r -= f / df;
  return std::clamp(r, 0.0, 1.0);
}

SgLobe specularLobe(glm::dvec3 n, glm::dvec3 omegaIn, double roughness) {
  const double alpha = std::max(roughness * roughness, kMinAlpha);
  const double alpha2 = alpha * alpha;
  // Dominant visible normal (centre of the spherical-cap VNDF, Dupuy and Benyoub 2023):
  // h ~ (alpha^2 w_xy, t + w_z) in the tangent frame, t = |(alpha w_xy, w_z)|. For w_z < 0,
  // t + w_z cancels; (t^2 - w_z^2) / (t - w_z) = alpha^2 |w_xy|^2 / (t - w_z) does not.
  const double wz = glm::dot(omegaIn, n);
  const glm::dvec3 wxy = omegaIn - wz * n;
  const double xy2 = glm::dot(wxy, wxy);
  const double t = std::sqrt(alpha2 * xy2 + wz * wz);
  const double z = wz >= 0.0 ? t + wz : alpha2 * xy2 / (t - wz);
  glm::dvec3 h = alpha2 * wxy + z * n;
  const double hLength = glm::length(h);
  // Zero only for light exactly from below (omegaIn = -n): no microfacet is visible and the VPL
  // carries no power; any axis keeps the result finite.
  h = hLength > 0.0 ? h / hLength : n;
  const double wh = glm::dot(omegaIn, h);
  SgLobe lobe;
  lobe.axis = glm::normalize(2.0 * wh * h - omegaIn);  // reflect(-omegaIn, h)
  // NDF sharpness ([TH19] via [R]), warped by the half-vector -> reflection Jacobian. The max
  // keeps 0 / 0 out of the rough limit (lambda_h = 0) if omegaIn . h underflows.
  const double lambdaH = 2.0 / alpha2 - 2.0;
  lobe.sharpness = std::min(
      lambdaH * glm::dot(h, n) / std::max(4.0 * std::abs(wh), std::numeric_limits<double>::min()),
      VSGL_MAX_SHARPNESS);
  return lobe;
}

double glossyShare(double sharpness) {
  const double x = std::log(std::max(sharpness, 1e-30) / VSGL_FLAT_SHARPNESS) /
                   std::log(VSGL_GLOSSY_SHARPNESS_RATIO);
  const double t = std::clamp(x, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

gpu::VsglLobe buildVsglLobe(const LobeSums& sums, glm::dvec3 origin) {
  gpu::VsglLobe lobe{};
  const double w = sums.power.w;
  if (!(w > 0.0)) {
    lobe.meanVariance = glm::vec4(glm::dvec4(origin, 0.0));
    lobe.axisSharpness = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
    lobe.power = glm::vec4(0.0f);
    return lobe;
  }
  const glm::dvec3 mean = glm::dvec3(sums.position) / w;
  // tr(Sigma) split over the two axes of the (assumed planar) cluster; the clamp absorbs the
  // cancellation of P2 / W - |mu|^2 for tight clusters (section 12 case 6).
  const double variance = std::max(0.0, sums.position.w / w - glm::dot(mean, mean)) / 2.0;
  const glm::dvec3 meanAxis = glm::dvec3(sums.axis) / w;
  const double meanLength = glm::length(meanAxis);
  SgLobe sg;  // opposing axes (length 0): isotropic, axis arbitrary (section 12 case 7)
  if (meanLength > 0.0) sg = {meanAxis / meanLength, banerjeeSharpness(meanLength)};
  lobe.meanVariance = glm::vec4(glm::dvec4(origin + mean, variance));
  lobe.axisSharpness = glm::vec4(glm::dvec4(sg.axis, sg.sharpness));
  lobe.power = glm::vec4(sums.power);
  return lobe;
}

double texelPatchArea(const TexelPatch& patch, glm::dvec3 offset, glm::dvec3 normal) {
  const glm::dvec3 w = patch.perspective ? glm::normalize(offset) : patch.axis;  // light -> y
  const double cosine =
      glm::dot(normal, normal) > 0.0 ? std::max(std::abs(glm::dot(normal, w)), 1e-6) : 1.0;
  if (!patch.perspective) return patch.texelArea / cosine;
  const double c = glm::dot(w, patch.axis);
  return patch.texelArea * c * c * c * glm::dot(offset, offset) / cosine;
}

bool kernelOffSurface(const std::array<VectorPyramid, VSGL_ATTR_COUNT>& attributes, glm::dvec2 x,
                      double level, glm::dvec3 surface, double tolerance) {
  const double diffuseWeight = sampleTrilinear(attributes[VSGL_ATTR_DIFFUSE_POWER], x, level).w;
  const double w =
      diffuseWeight + sampleTrilinear(attributes[VSGL_ATTR_SPECULAR_POWER], x, level).w;
  const glm::dvec3 axis(sampleTrilinear(attributes[VSGL_ATTR_DIFFUSE_AXIS], x, level));
  if (!(diffuseWeight > 0.0) || !(glm::dot(axis, axis) > 0.0)) return false;
  const glm::dvec4 sums = sampleTrilinear(attributes[VSGL_ATTR_DIFFUSE_POSITION], x, level) +
                          sampleTrilinear(attributes[VSGL_ATTR_SPECULAR_POSITION], x, level);
  const glm::dvec3 mean = glm::dvec3(sums) / w;
  const double variance = std::max(sums.w / w - glm::dot(mean, mean), 0.0) / 2.0;
  const double planarity = vsglPlanarity(banerjeeSharpness(glm::length(axis) / diffuseWeight));
  const double h = planarity * glm::dot(mean - surface, glm::normalize(axis));
  return h * h > tolerance * tolerance * variance;
}

double surfaceLevel(const std::array<VectorPyramid, VSGL_ATTR_COUNT>& attributes, glm::dvec2 x,
                    double level, glm::dvec3 surface, double tolerance) {
  double lo = 0.0;
  while (lo < level) {
    double hi = std::min(lo + VSGL_SURFACE_SCAN_STEP, level);
    if (kernelOffSurface(attributes, x, hi, surface, tolerance)) {
      for (int step = 0; step < VSGL_SURFACE_BISECTION_STEPS; ++step) {
        const double mid = 0.5 * (lo + hi);
        (kernelOffSurface(attributes, x, mid, surface, tolerance) ? hi : lo) = mid;
      }
      return lo;
    }
    lo = hi;
  }
  return level;
}

std::vector<gpu::Vsgl> generateVsglsReference(
    const std::array<VectorPyramid, VSGL_ATTR_COUNT>& attributes, const ScalarPyramid& pdf,
    glm::dvec3 origin, uint32_t n, double k, uint32_t rule, const TexelPatch& patch,
    double surfaceTolerance) {
  const double top = topMean(pdf);
  const uint32_t texelCount = pdf.size * pdf.size;
  std::vector<gpu::Vsgl> vsgls(n);
  for (uint32_t i = 0; i < n; ++i) {
    WarpResult warp = warpHierarchical(pdf, fibonacciPoint(i, n));
    const bool modified = rule == VSGL_RULE_MODIFIED, point = rule == VSGL_RULE_POINT;
    // A VPL reads its texel alone: level 0 at the texel's centre.
    if (point) warp.x = (glm::dvec2(warp.texel) + 0.5) / double(pdf.size);
    // The surface under x: the power-weighted level-0 position bilinearly around it, also the
    // ISM's centre.
    const double weight = sampleTrilinear(attributes[VSGL_ATTR_DIFFUSE_POWER], warp.x, 0.0).w +
                          sampleTrilinear(attributes[VSGL_ATTR_SPECULAR_POWER], warp.x, 0.0).w;
    const glm::dvec3 surface =
        (glm::dvec3(sampleTrilinear(attributes[VSGL_ATTR_DIFFUSE_POSITION], warp.x, 0.0)) +
         glm::dvec3(sampleTrilinear(attributes[VSGL_ATTR_SPECULAR_POSITION], warp.x, 0.0))) /
        std::max(weight, 1e-300);
    double level = point      ? 0.0
                   : modified ? modifiedFisLevel(pdf, warp.x, n, k)
                              : tok15Level(warp.density, n, k, pdf.size);
    if (!point && surfaceTolerance > 0.0 && weight > 0.0)
      level = surfaceLevel(attributes, warp.x, level, surface, surfaceTolerance);
    const double filtered = top > 0.0 ? sampleTrilinear(pdf, warp.x, level) / top : 0.0;
    // An all-zero PDF has no mass to share: zero power rather than [T15]'s M F~ / 1. A VPL is
    // its texel's value over N p, the importance-sampling estimator, as modified FIS at l = 0.
    const double scale = !(top > 0.0)        ? 0.0
                         : modified || point ? modifiedFisScale(filtered, n, texelCount)
                                             : tok15Scale(warp.density, n, texelCount);
    // Numerators and denominators of every ratio come from the same kernel (section 3.5).
    auto sums = [&](int power, int position, int axis) {
      return LobeSums{scale * sampleTrilinear(attributes[power], warp.x, level),
                      scale * sampleTrilinear(attributes[position], warp.x, level),
                      scale * sampleTrilinear(attributes[axis], warp.x, level)};
    };
    gpu::Vsgl& vsgl = vsgls[i];
    vsgl.diffuse = buildVsglLobe(
        sums(VSGL_ATTR_DIFFUSE_POWER, VSGL_ATTR_DIFFUSE_POSITION, VSGL_ATTR_DIFFUSE_AXIS), origin);
    vsgl.specular = buildVsglLobe(
        sums(VSGL_ATTR_SPECULAR_POWER, VSGL_ATTR_SPECULAR_POSITION, VSGL_ATTR_SPECULAR_AXIS),
        origin);
    if (point && vsgl.diffuse.power.a + vsgl.specular.power.a > 0.0f) {
      // Never less than the texel itself: as N grows the VPL becomes its texel.
      const bool hasNormal = vsgl.diffuse.power.a > 0.0f;
      const glm::dvec3 mean(hasNormal ? vsgl.diffuse.meanVariance : vsgl.specular.meanVariance);
      const glm::dvec3 normal =
          hasNormal ? glm::dvec3(vsgl.diffuse.axisSharpness) : glm::dvec3(0.0);
      const double area = texelPatchArea(patch, mean - origin, normal) * std::max(1.0, scale);
      vsgl.diffuse.meanVariance.w = vsgl.specular.meanVariance.w =
          float(area / (4.0 * std::numbers::pi));
    }
    vsgl.kernel = glm::vec4(glm::dvec4(warp.x, level, filtered));
    if (weight > 0.0) vsgl.visibilityPoint = glm::vec4(glm::dvec4(origin + surface, 1.0));
  }
  return vsgls;
}

}  // namespace gi
