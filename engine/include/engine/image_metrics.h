// Error metrics of a rendered linear-HDR image against a reference (tests, the benchmark,
// flicker captures), split by the kind of surface a pixel shows, and a false-colour picture of
// where the error is.
//
// Images are width * height linear RGB values in double, row-major, as std::span<const dvec3>;
// the optional class mask has one PixelClass per pixel in the same order. Mismatched sizes
// throw engine::Error with a one-line message naming both sizes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace engine {

struct GBufferSample;
struct GBufferData;

enum class PixelClass : uint8_t { Excluded = 0, Diffuse = 1, Glossy = 2 };

// Background -> Excluded; perceptual roughness <= kGlossyRoughness -> Glossy; else Diffuse.
// The class is about the lobe width, not the material: a rough metal is Diffuse, a smooth
// plastic Glossy, because what matters for the error is whether it moves with the view.
PixelClass classifyPixel(const GBufferSample& s);

// classifyPixel of every texel, row-major like the G-buffer.
std::vector<PixelClass> classifyPixels(const GBufferData& g);

struct ErrorMetrics {
  size_t pixels = 0;         // pixels averaged: counted by the class filter, test finite
  size_t nonFinite = 0;      // pixels counted by the class filter whose test value is NaN/Inf
  double rmse = 0;           // sqrt(mean over pixels and channels of (t - r)^2)
  double relativeMse = 0;    // mean of (t - r)^2 / (r^2 + kRelativeMseEpsilon), see the .cpp
  double psnr = 0;           // dB, peak = largest reference channel value over the pixels
  double referenceMean = 0;  // mean reference channel value over the pixels
};

// Compares `test` with `reference`. Pixels counted: all when `classes` is empty; otherwise
// those whose class is not Excluded and, when `only` is set, equal to *only (`only` without a
// mask throws). Counted pixels with a non-finite test channel are left out of every average
// and counted in nonFinite, so a NaN in a method's output shows in a report instead of
// poisoning the numbers; a non-finite reference value on a counted pixel throws, since no
// metric against a broken reference means anything.
// psnr = 10 log10(peak^2 / mse) on linear values: +inf when mse == 0, -inf when the reference
// is black there but the test is not. With no pixel left every metric is 0.
ErrorMetrics compareImages(std::span<const glm::dvec3> test, std::span<const glm::dvec3> reference,
                           std::span<const PixelClass> classes = {},
                           std::optional<PixelClass> only = std::nullopt);

struct SplitMetrics {
  ErrorMetrics all;  // every pixel not Excluded
  ErrorMetrics diffuse;
  ErrorMetrics glossy;
};

// compareImages over all non-excluded pixels, the Diffuse ones and the Glossy ones; `classes`
// must hold one class per pixel.
SplitMetrics compareImagesSplit(std::span<const glm::dvec3> test,
                                std::span<const glm::dvec3> reference,
                                std::span<const PixelClass> classes);

// RGBA8 picture (test.size() * 4 bytes) of e = |Y(test) - Y(reference)|, Y the Rec. 709
// luminance, mapped linearly from [0, maxError] onto the viridis colour map (larger errors
// clamp to its last colour; maxError 0 draws every non-zero error in it), alpha 255. Pixels
// with a non-finite value in either image are magenta (255, 0, 255). maxError must be >= 0.
std::vector<uint8_t> falseColourError(std::span<const glm::dvec3> test,
                                      std::span<const glm::dvec3> reference, double maxError);

// falseColourError written as a PNG (engine::writePng); width * height must equal the images'
// size. Throws engine::Error("<path>: <problem>") when the file cannot be written.
void writeFalseColourError(const std::string& pngPath, int width, int height,
                           std::span<const glm::dvec3> test, std::span<const glm::dvec3> reference,
                           double maxError);

// The q-quantile (q in [0, 1], nearest rank) of the same per-pixel error as falseColourError,
// over the pixels finite in both images; 0 when there are none. q = 0.99 gives a maxError that
// a handful of fireflies cannot wash the picture out with.
double percentileAbsError(std::span<const glm::dvec3> test, std::span<const glm::dvec3> reference,
                          double q);

}  // namespace engine
