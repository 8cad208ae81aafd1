// CPU twin of the direct lighting pass (shaders/lighting/direct_light.comp): the same BRDF
// (Lambert + GGX with height-correlated Smith visibility + Schlick Fresnel, common/brdf.glsl),
// inverse-square falloff with KHR_lights_punctual's range window and spot cone falloff, and
// the same normal-offset 3x3 PCF of the shadow maps, evaluated in double.
//
// The GPU rebuilds the receiver from the fp32 depth with an fp32 inverse view-projection; with
// a perspective camera that loses digits to cancellation (h.w ~ 1 - depth), so the GPU's
// receiver sits anywhere within a few depth ulps along the view ray of the exact one. Shading
// is smooth in the receiver except at shadow-map decisions, so the reference reports, next to
// its radiance, how much the radiance changes over that interval (`spread`), and flags pixels
// where a shadow test is within fp32 rounding of its threshold (`ambiguous`): a tap that may
// go either way changes the result by a ninth of a light's contribution, and no tolerance on
// values can absorb that.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/direct_light.h"
#include "engine/gbuffer_reference.h"
#include "engine/view.h"

namespace engine {

// Receiver position uncertainty of the GPU, in ulps of the G-buffer depth: h = M (x, y, z, 1)
// in fp32 rounds four products and three sums, each at most half an ulp of the largest term;
// for h.w the terms are ~1/znear and cancel to (1 - z)/znear, which is the same absolute
// error as moving z by about one ulp. Four leaves room for the division and for FMA-less
// evaluation orders.
constexpr int kReceiverDepthUlps = 4;

// Shadow decisions closer than this to their threshold, in NDC units, count as ambiguous:
// 16 ulps of values in [0.5, 1), covering fp32 rounding in the shadow view's 4x4 transform
// (terms a few times larger than w) and the perspective division.
constexpr double kShadowNdcMargin = 0x1p-20;

struct DirectLightReference {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::dvec3> radiance;  // W sr^-1 m^-2 at the receiver rebuilt from depth; 0 on background
  // Per pixel, the largest change of any radiance channel when the receiver moves
  // kReceiverDepthUlps depth ulps either way along the view ray.
  std::vector<double> spread;
  std::vector<uint8_t> ambiguous;  // 1 where a shadow test is within kShadowNdcMargin of flipping
};

// The shadow maps of every view in `setup`, rendered by rasterizeReference and laid out as the
// GPU's buffer: resolution^2 visibility texels per view, views back to back.
std::vector<uint64_t> shadowMapsReference(const Scene& scene, const LightSetup& setup,
                                          uint32_t resolution);

// Radiance of every G-buffer pixel lit by setup.lights; `shadowMaps` holds the views of
// setup.views as shadowMapsReference lays them out (may be empty when no light has views).
DirectLightReference directLightReference(const GBufferData& gbuffer, const View& view,
                                          const LightSetup& setup, uint32_t shadowResolution,
                                          std::span<const uint64_t> shadowMaps);

}  // namespace engine
