// This work is based on:
// - F. Rousselle, C. Knaus, M. Zwicker, "Adaptive Sampling and Reconstruction using Greedy
//   Error Minimization", ACM TOG 30(6) (SIGGRAPH Asia 2011): the relative MSE.
// - S. van der Walt, N. Smith, "viridis" colour map (matplotlib 1.5, 2015): the false colours.
#include "engine/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/error.h"
#include "engine/gbuffer_reference.h"
#include "engine/image_io.h"

namespace engine {
namespace {

// Perceptual roughness at or below which a pixel is Glossy. GGX alpha = 0.5^2 = 0.25 is a
// lobe narrow enough that its highlight moves with the view, which is where glossy indirect
// light is hard and flickers; broader lobes reflect a blurred, nearly view-independent
// average and fail the way diffuse surfaces do.
constexpr double kGlossyRoughness = 0.5;

// relMSE = (t - r)^2 / (r^2 + eps) per channel (Rousselle et al. 2011), the "relMSE" most
// denoising papers report. eps = 0.01 keeps black reference pixels from dominating: below a
// reference value of ~0.1 the error counts as absolute rather than relative.
constexpr double kRelativeMseEpsilon = 1e-2;

// Rec. ITU-R BT.709 luminance weights for linear RGB with the sRGB/Rec. 709 primaries.
constexpr glm::dvec3 kLuminanceWeights{0.2126, 0.7152, 0.0722};

// viridis sampled at every 16th of its 256 published entries and the last one; the entry at
// index i sits at i / 255 along the map. Values are sRGB-encoded display colours, written to the
// PNG as they are.
struct ViridisPoint {
  int index;
  glm::dvec3 colour;
};
constexpr int kViridisLastIndex = 255;
constexpr std::array<ViridisPoint, 17> kViridis{{
    {0, {0.267004, 0.004874, 0.329415}},
    {16, {0.282327, 0.094955, 0.417331}},
    {32, {0.278826, 0.175490, 0.483397}},
    {48, {0.258965, 0.251537, 0.524736}},
    {64, {0.229739, 0.322361, 0.545706}},
    {80, {0.199430, 0.387607, 0.554642}},
    {96, {0.172719, 0.448791, 0.557885}},
    {112, {0.149039, 0.508051, 0.557250}},
    {128, {0.127568, 0.566949, 0.550556}},
    {144, {0.120638, 0.625828, 0.533488}},
    {160, {0.157851, 0.683765, 0.501686}},
    {176, {0.246070, 0.738910, 0.452024}},
    {192, {0.369214, 0.788888, 0.382914}},
    {208, {0.515992, 0.831158, 0.294279}},
    {224, {0.678489, 0.863742, 0.189503}},
    {240, {0.845561, 0.887322, 0.099702}},
    {255, {0.993248, 0.906157, 0.143936}},
}};

constexpr std::array<uint8_t, 4> kNonFiniteColour{255, 0, 255, 255};

bool isFinite(const glm::dvec3& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

double luminance(const glm::dvec3& c) {
  return glm::dot(kLuminanceWeights, c);
}

void checkSameSize(const char* what, std::span<const glm::dvec3> test,
                   std::span<const glm::dvec3> reference) {
  if (test.size() != reference.size()) {
    throw Error(std::string(what) + ": test has " + std::to_string(test.size()) +
                " pixels, reference has " + std::to_string(reference.size()));
  }
}

// t in [0, 1] -> viridis, linear between the control points.
glm::dvec3 viridis(double t) {
  const double position = std::clamp(t, 0.0, 1.0) * kViridisLastIndex;
  size_t i = 1;
  while (i + 1 < kViridis.size() && position > kViridis[i].index) ++i;
  const ViridisPoint& lo = kViridis[i - 1];
  const ViridisPoint& hi = kViridis[i];
  return glm::mix(lo.colour, hi.colour, (position - lo.index) / (hi.index - lo.index));
}

uint8_t toUnorm8(double x) {
  return static_cast<uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0));
}

}  // namespace

PixelClass classifyPixel(const GBufferSample& s) {
  if (s.background()) return PixelClass::Excluded;
  return s.roughness <= kGlossyRoughness ? PixelClass::Glossy : PixelClass::Diffuse;
}

std::vector<PixelClass> classifyPixels(const GBufferData& g) {
  std::vector<PixelClass> classes;
  classes.reserve(g.samples.size());
  for (const GBufferSample& s : g.samples) classes.push_back(classifyPixel(s));
  return classes;
}

ErrorMetrics compareImages(std::span<const glm::dvec3> test, std::span<const glm::dvec3> reference,
                           std::span<const PixelClass> classes, std::optional<PixelClass> only) {
  checkSameSize("compareImages", test, reference);
  if (!classes.empty() && classes.size() != reference.size()) {
    throw Error("compareImages: class mask has " + std::to_string(classes.size()) +
                " entries, images have " + std::to_string(reference.size()) + " pixels");
  }
  if (classes.empty() && only) {
    throw Error("compareImages: a class filter needs a class mask");
  }

  ErrorMetrics m;
  // Sums in double over at most a few million values: no compensated summation needed.
  double squaredError = 0.0, relativeError = 0.0, referenceSum = 0.0, peak = 0.0;
  for (size_t i = 0; i < reference.size(); ++i) {
    if (!classes.empty()) {
      if (classes[i] == PixelClass::Excluded || (only && classes[i] != *only)) continue;
    }
    const glm::dvec3& r = reference[i];
    if (!isFinite(r)) {
      throw Error("compareImages: reference pixel " + std::to_string(i) + " is not finite");
    }
    const glm::dvec3& t = test[i];
    if (!isFinite(t)) {
      ++m.nonFinite;
      continue;
    }
    ++m.pixels;
    for (int c = 0; c < 3; ++c) {
      const double d2 = (t[c] - r[c]) * (t[c] - r[c]);
      squaredError += d2;
      relativeError += d2 / (r[c] * r[c] + kRelativeMseEpsilon);
      referenceSum += r[c];
      peak = std::max(peak, r[c]);
    }
  }
  if (m.pixels == 0) return m;

  const double values = 3.0 * static_cast<double>(m.pixels);
  const double mse = squaredError / values;
  m.rmse = std::sqrt(mse);
  m.relativeMse = relativeError / values;
  m.referenceMean = referenceSum / values;
  m.psnr =
      mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(peak * peak / mse);
  return m;
}

SplitMetrics compareImagesSplit(std::span<const glm::dvec3> test,
                                std::span<const glm::dvec3> reference,
                                std::span<const PixelClass> classes) {
  if (classes.size() != reference.size()) {
    throw Error("compareImagesSplit: class mask has " + std::to_string(classes.size()) +
                " entries, images have " + std::to_string(reference.size()) + " pixels");
  }
  return {compareImages(test, reference, classes),
          compareImages(test, reference, classes, PixelClass::Diffuse),
          compareImages(test, reference, classes, PixelClass::Glossy)};
}

std::vector<uint8_t> falseColourError(std::span<const glm::dvec3> test,
                                      std::span<const glm::dvec3> reference, double maxError) {
  checkSameSize("falseColourError", test, reference);
  if (!(maxError >= 0.0)) {
    throw Error("falseColourError: maxError " + std::to_string(maxError) + " is not >= 0");
  }
  std::vector<uint8_t> rgba(test.size() * 4);
  for (size_t i = 0; i < test.size(); ++i) {
    uint8_t* out = &rgba[i * 4];
    if (!isFinite(test[i]) || !isFinite(reference[i])) {
      std::copy(kNonFiniteColour.begin(), kNonFiniteColour.end(), out);
      continue;
    }
    const double e = std::abs(luminance(test[i]) - luminance(reference[i]));
    // maxError 0 (identical images, a 0 percentile) must not divide by zero.
    const double t = maxError > 0.0 ? e / maxError : (e > 0.0 ? 1.0 : 0.0);
    const glm::dvec3 colour = viridis(t);
    out[0] = toUnorm8(colour.r);
    out[1] = toUnorm8(colour.g);
    out[2] = toUnorm8(colour.b);
    out[3] = 255;
  }
  return rgba;
}

void writeFalseColourError(const std::string& pngPath, int width, int height,
                           std::span<const glm::dvec3> test, std::span<const glm::dvec3> reference,
                           double maxError) {
  if (width <= 0 || height <= 0 ||
      static_cast<size_t>(width) * static_cast<size_t>(height) != reference.size()) {
    throw Error(pngPath + ": " + std::to_string(width) + "x" + std::to_string(height) +
                " does not match the images' " + std::to_string(reference.size()) + " pixels");
  }
  writePng(pngPath, width, height, falseColourError(test, reference, maxError));
}

double percentileAbsError(std::span<const glm::dvec3> test, std::span<const glm::dvec3> reference,
                          double q) {
  checkSameSize("percentileAbsError", test, reference);
  if (!(q >= 0.0 && q <= 1.0)) {
    throw Error("percentileAbsError: q " + std::to_string(q) + " is not in [0, 1]");
  }
  std::vector<double> errors;
  errors.reserve(test.size());
  for (size_t i = 0; i < test.size(); ++i) {
    if (isFinite(test[i]) && isFinite(reference[i])) {
      errors.push_back(std::abs(luminance(test[i]) - luminance(reference[i])));
    }
  }
  if (errors.empty()) return 0.0;
  // Nearest rank: the smallest error with at least a fraction q of the pixels at or below it.
  const double rank = std::ceil(q * static_cast<double>(errors.size()));
  const size_t k = std::clamp(static_cast<size_t>(rank), size_t{1}, errors.size()) - 1;
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
  return errors[k];
}

BlockMeans blockMeans(std::span<const glm::dvec3> image, uint32_t width, uint32_t height,
                      uint32_t block, std::span<const uint8_t> valid) {
  if (block == 0) throw Error("blockMeans: block size 0");
  if (image.size() != size_t{width} * height || (!valid.empty() && valid.size() != image.size()))
    throw Error("blockMeans: " + std::to_string(image.size()) + " pixels for a " +
                std::to_string(width) + "x" + std::to_string(height) + " image");
  BlockMeans b{width / block, height / block, {}, {}};
  b.means.assign(size_t{b.width} * b.height, glm::dvec3(0.0));
  b.valid.assign(b.means.size(), 0);
  for (uint32_t by = 0; by < b.height; ++by)
    for (uint32_t bx = 0; bx < b.width; ++bx) {
      glm::dvec3 sum(0.0);
      uint32_t count = 0;
      for (uint32_t y = by * block; y < (by + 1) * block; ++y)
        for (uint32_t x = bx * block; x < (bx + 1) * block; ++x) {
          const size_t i = size_t{y} * width + x;
          if (!valid.empty() && !valid[i]) continue;
          sum += image[i];
          ++count;
        }
      const size_t k = size_t{by} * b.width + bx;
      if (2 * count < block * block || count == 0) continue;
      b.means[k] = sum / double(count);
      b.valid[k] = 1;
    }
  return b;
}

double temporalError(std::span<const glm::dvec3> previous, std::span<const glm::dvec3> current,
                     std::span<const glm::dvec3> previousReference,
                     std::span<const glm::dvec3> currentReference, std::span<const uint8_t> valid) {
  checkSameSize("temporalError", previous, current);
  checkSameSize("temporalError", previousReference, currentReference);
  checkSameSize("temporalError", current, currentReference);
  if (!valid.empty() && valid.size() != current.size())
    throw Error("temporalError: mask has " + std::to_string(valid.size()) + " entries, images " +
                std::to_string(current.size()) + " pixels");
  double squared = 0.0, referenceSum = 0.0;
  size_t pixels = 0;
  for (size_t i = 0; i < current.size(); ++i) {
    if (!valid.empty() && !valid[i]) continue;
    ++pixels;
    if (!isFinite(previous[i]) || !isFinite(current[i]) || !isFinite(previousReference[i]) ||
        !isFinite(currentReference[i]))
      throw Error("temporalError: pixel " + std::to_string(i) + " is not finite");
    const glm::dvec3 change =
        (current[i] - currentReference[i]) - (previous[i] - previousReference[i]);
    squared += glm::dot(change, change);
    for (int c = 0; c < 3; ++c) referenceSum += previousReference[i][c] + currentReference[i][c];
  }
  if (pixels == 0) return 0.0;
  const double values = 3.0 * static_cast<double>(pixels);
  const double rms = std::sqrt(squared / values);
  const double mean = referenceSum / (2.0 * values);
  return mean > 0.0 ? rms / mean : rms;
}

}  // namespace engine
