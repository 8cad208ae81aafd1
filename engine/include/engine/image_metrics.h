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

// Means of `block` x `block` pixel blocks of a width x height image over the pixels whose
// `valid` entry is not 0 (all, when `valid` is empty); partial blocks at the right and bottom
// edges are dropped. A block is valid when at least half of its pixels are; an invalid block's
// mean is 0. The flicker figure compares block means: the per-pixel noise of a reference (a
// path tracer's, or a VPL gather's point-like highlights) averages out, while a VSGL's jump,
// which lights many pixels at once, does not (docs/flicker.md).
struct BlockMeans {
  uint32_t width = 0, height = 0;  // in blocks
  std::vector<glm::dvec3> means;
  std::vector<uint8_t> valid;
};
BlockMeans blockMeans(std::span<const glm::dvec3> image, uint32_t width, uint32_t height,
                      uint32_t block, std::span<const uint8_t> valid = {});

// Flicker between two consecutive frames (docs/flicker.md): the RMS over pixels and channels of
// the change of the error image, (I_t - R_t) - (I_t-1 - R_t-1), over the mean channel value of
// the two reference frames (the plain RMS when both are black). Motion that the reference shows
// moves I and R alike and cancels, so what is left is change the reference does not have. It
// is exactly 0 when neither image changed. Every image must be finite and of one size. With a
// `valid` mask (one entry per pixel), pixels whose entry is 0 are left out: a moving camera's
// caller passes the previous frame reprojected and leaves out what it could not reproject.
double temporalError(std::span<const glm::dvec3> previous, std::span<const glm::dvec3> current,
                     std::span<const glm::dvec3> previousReference,
                     std::span<const glm::dvec3> currentReference,
                     std::span<const uint8_t> valid = {});

}  // namespace engine
