// The one-bounce ground truth (issue 5): a CPU path tracer on Embree, independent of the RSM,
// that renders what the VSGL module approximates, in the same units, BRDF and camera:
//   direct:  every light, exact shadow rays, plus the visible surface's emission (glTF emissive,
//            which does not bounce: engine::Material::emissiveFactor);
//   diffuse, glossy: light of ONE light (the one the RSM renders) after exactly one bounce,
//            light -> y -> x -> camera, split by the receiver x's lobe (Lambert or GGX) as the
//            module's two outputs are. y reflects with its full BRDF (both lobes).
// Primary rays go through pixel centres as the G-buffer's do (one visible point per pixel, no
// anti-aliasing), so images compare pixel by pixel with the GPU's.
//
// Estimator at x: three strategies for the bounce point y, combined by the balance heuristic
// (Veach 1997, section 9.2.2): (a) directions from a one-sample mixture of cosine and GGX
// visible-normal sampling (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"), the
// light at y (a point or direction) evaluated exactly with a shadow ray; (b) rays from the light;
// (c) y around a near-mirror plane's reflection of the light (mirror_planes.h), in one mixture
// with (a). Each pixel has its own PCG32 stream seeded from (seed, pixel), so the image does not
// depend on the thread count or scheduling.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "embree_scene.h"
#include "engine/scene.h"
#include "engine/view.h"
#include "reference_cache.h"

namespace truth {

// How many samples a pixel gets: enough, by two sizing runs (a pilot of minSamples, then a
// quarter of the predicted count; both discarded), for the standard error of its indirect
// luminance (Rec. 709) to reach relativeError of its mean, or relativeError x floorFraction of
// the image's mean indirect luminance, whichever is larger; within [minSamples, maxSamples].
struct PathTraceSettings {
  double relativeError = 0.01;
  double floorFraction = 0.1;
  uint32_t minSamples = 256;
  uint32_t maxSamples = 1u << 16;
  uint64_t seed = 1;
  unsigned threads = 0;   // 0: std::thread::hardware_concurrency()
  bool progress = false;  // progress lines on stderr
  // Off: the direct light ignores occluders (to compare with a renderer's unshadowed mode; the
  // one-bounce light always traces its shadow rays).
  bool directShadows = true;
  // Strategy (c), the bounce point sampled around near-mirror planes' reflections of the light
  // (mirror_planes.h); off, (a) and (b) alone (tests compare the two).
  bool mirrorSampling = true;
};

struct PathTraceImage {
  uint32_t width = 0;
  uint32_t height = 0;
  // Radiance towards the camera, W sr^-1 m^-2, row 0 at the top; 0 on background pixels.
  std::vector<glm::dvec3> direct;
  std::vector<glm::dvec3> diffuse;
  std::vector<glm::dvec3> glossy;
  std::vector<double> standardError;  // of the luminance of diffuse + glossy, per pixel
  std::vector<uint32_t> samples;      // per pixel (0 on background)
  double noiseFloor = 0.0;            // the absolute standard-error target (see settings)
  // Final standard error over its target, median and 95th percentile over the pixels: the
  // counts aim at 1, so about half the pixels land a little above it; the 95th percentile
  // shows how far the heavy tails of the worst pixels escaped the sizing runs.
  double medianErrorRatio = 0.0;
  double p95ErrorRatio = 0.0;
  double seconds = 0.0;
};

// `bouncingLight` indexes scene.lights. Throws engine::Error on an index out of range.
PathTraceImage pathTrace(const engine::Scene& scene, const EmbreeScene& rays,
                         const engine::View& view, uint32_t bouncingLight,
                         const PathTraceSettings& settings);
// The same with the light of every index in `bouncingLights` bouncing: diffuse and glossy sum
// their one-bounce light (each light with its own three strategies in every sample).
PathTraceImage pathTrace(const engine::Scene& scene, const EmbreeScene& rays,
                         const engine::View& view, std::span<const uint32_t> bouncingLights,
                         const PathTraceSettings& settings);

// pathTrace through `cache`: the stored image when one exists for these inputs (scene content,
// view, light, settings except threads and progress), else rendered and stored. `fromCache`
// says which. The EmbreeScene is built only when rendering.
PathTraceImage cachedPathTrace(const ReferenceCache& cache, const engine::Scene& scene,
                               const engine::View& view, uint32_t bouncingLight,
                               const PathTraceSettings& settings, bool* fromCache = nullptr);
PathTraceImage cachedPathTrace(const ReferenceCache& cache, const engine::Scene& scene,
                               const engine::View& view, std::span<const uint32_t> bouncingLights,
                               const PathTraceSettings& settings, bool* fromCache = nullptr);

}  // namespace truth
