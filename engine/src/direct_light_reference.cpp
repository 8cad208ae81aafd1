#include "engine/direct_light_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>

#include "engine/error.h"
#include "engine/raster_reference.h"
#include "shared/raster.h"

namespace engine {
namespace {

// common/brdf.glsl's constants.
constexpr double kMinAlpha = 1e-3;
constexpr double kMinNv = 1e-4;

double ggxD(double nh, double a2) {
  double d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (std::numbers::pi * d * d);
}

double smithGgxCorrelatedV(double nv, double nl, double a2) {
  double gv = nl * std::sqrt(nv * nv * (1.0 - a2) + a2);
  double gl = nv * std::sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / std::max(gv + gl, 1e-12);
}

glm::dvec3 schlickFresnel(glm::dvec3 f0, double vh) {
  double m = 1.0 - vh;
  return f0 + (1.0 - f0) * std::pow(m, 5.0);
}

glm::dvec3 brdfCos(glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, const GBufferSample& s) {
  double nl = glm::dot(n, l);
  double nv = std::max(glm::dot(n, v), kMinNv);
  if (nl <= 0.0) return glm::dvec3(0.0);
  double alpha = std::max(s.roughness * s.roughness, kMinAlpha);
  double a2 = alpha * alpha;
  glm::dvec3 h = glm::normalize(v + l);
  double nh = std::max(glm::dot(n, h), 0.0);
  glm::dvec3 spec = ggxD(nh, a2) * smithGgxCorrelatedV(nv, nl, a2) *
                    schlickFresnel(s.f0, std::max(glm::dot(v, h), 0.0));
  return (s.diffuse / std::numbers::pi + spec) * nl;
}

glm::dvec3 unproject(const glm::dmat4& invViewProj, glm::dvec2 ndc, double z) {
  glm::dvec4 h = invViewProj * glm::dvec4(ndc, z, 1.0);
  return glm::dvec3(h) / h.w;
}

struct Visibility {
  double lit = 1.0;
  bool ambiguous = false;
};

bool nearInteger(double x, double margin) { return std::abs(x - std::round(x)) <= margin; }

// The shader's shadowVisibility(): fraction of the 3x3 texels around p's projection that see p.
Visibility shadowVisibility(const gpu::ShadowView& view, std::span<const uint64_t> map, int size,
                            glm::dvec3 p) {
  glm::dvec4 clip = glm::dmat4(view.viewProj) * glm::dvec4(p, 1.0);
  if (clip.w <= 0.0) return {};
  glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  Visibility r;
  r.ambiguous = std::abs(ndc.z) <= kShadowNdcMargin || std::abs(ndc.z - 1.0) <= kShadowNdcMargin;
  if (ndc.z < 0.0 || ndc.z > 1.0) return r;
  glm::dvec2 texel = (glm::dvec2(ndc) * 0.5 + 0.5) * static_cast<double>(size);
  // An NDC error of kShadowNdcMargin moves the texel coordinate by margin * size / 2.
  double texelMargin = kShadowNdcMargin * 0.5 * size;
  r.ambiguous = r.ambiguous || nearInteger(texel.x, texelMargin) || nearInteger(texel.y, texelMargin);
  glm::ivec2 centre(static_cast<int>(std::floor(texel.x)), static_cast<int>(std::floor(texel.y)));
  double lit = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      glm::ivec2 t = glm::clamp(centre + glm::ivec2(dx, dy), glm::ivec2(0), glm::ivec2(size - 1));
      auto hi = static_cast<uint32_t>(map[static_cast<size_t>(t.y) * size + t.x] >> 32);
      if (hi == RASTER_EMPTY_HI) {
        lit += 1.0;
        continue;
      }
      double stored = std::bit_cast<float>(hi);
      lit += ndc.z <= stored ? 1.0 : 0.0;
      r.ambiguous = r.ambiguous || std::abs(ndc.z - stored) <= kShadowNdcMargin;
    }
  r.lit = lit / 9.0;
  return r;
}

// The shader's cubeFace(), plus whether the two largest axes tie within rounding.
uint32_t cubeFace(glm::dvec3 d, bool& ambiguous) {
  glm::dvec3 a = glm::abs(d);
  double sorted[3] = {a.x, a.y, a.z};
  std::sort(sorted, sorted + 3);
  ambiguous = ambiguous || sorted[2] - sorted[1] <= kShadowNdcMargin * sorted[2];
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y >= 0.0 ? 2u : 3u;
  return d.z >= 0.0 ? 4u : 5u;
}

struct Shading {
  glm::dvec3 radiance{0.0};
  bool ambiguous = false;
};

struct Lighting {
  const LightSetup& setup;
  int shadowResolution;
  std::span<const uint64_t> shadowMaps;
};

// The body of the shader's light loop for receiver p with unit normal n and view vector v.
Shading shade(const Lighting& lighting, const GBufferSample& s, glm::dvec3 p, glm::dvec3 v) {
  Shading out;
  const size_t mapTexels = static_cast<size_t>(lighting.shadowResolution) * lighting.shadowResolution;
  for (const gpu::GpuLight& light : lighting.setup.lights) {
    glm::dvec3 l;
    glm::dvec3 irradiance(light.radiance);
    double distanceToLight = 0.0;
    if (light.info.x == LIGHT_DIRECTIONAL) {
      l = -glm::dvec3(light.direction);
    } else {
      glm::dvec3 toLight = glm::dvec3(light.position) - p;
      double d2 = std::max(glm::dot(toLight, toLight), 1e-8);
      distanceToLight = std::sqrt(d2);
      l = toLight / distanceToLight;
      irradiance /= d2;
      double range = light.radiance.w;
      if (range > 0.0) {
        double r = distanceToLight / range;
        irradiance *= std::clamp(1.0 - r * r * r * r, 0.0, 1.0);
      }
      if (light.info.x == LIGHT_SPOT) {
        double cd = glm::dot(glm::dvec3(light.direction), -l);
        double falloff = std::clamp(cd * light.spot.x + light.spot.y, 0.0, 1.0);
        irradiance *= falloff * falloff;
      }
    }
    glm::dvec3 f = brdfCos(s.normal, v, l, s);
    if (f == glm::dvec3(0.0) || irradiance == glm::dvec3(0.0)) continue;
    double visibility = 1.0;
    if (light.info.z > 0u) {
      uint32_t view = light.info.y;
      if (light.info.z == 6u) view += cubeFace(p - glm::dvec3(light.position), out.ambiguous);
      const gpu::ShadowView& shadowView = lighting.setup.views[view];
      double texelWorld = shadowView.texel.x * distanceToLight + shadowView.texel.y;
      glm::dvec3 offset = s.normal * (SHADOW_NORMAL_OFFSET_TEXELS * texelWorld);
      Visibility vis = shadowVisibility(shadowView, lighting.shadowMaps.subspan(view * mapTexels, mapTexels),
                                        lighting.shadowResolution, p + offset);
      visibility = vis.lit;
      out.ambiguous = out.ambiguous || vis.ambiguous;
    }
    out.radiance += f * irradiance * visibility;
  }
  return out;
}

}  // namespace

std::vector<uint64_t> shadowMapsReference(const Scene& scene, const LightSetup& setup,
                                          uint32_t resolution) {
  std::vector<uint64_t> maps;
  maps.reserve(setup.views.size() * resolution * resolution);
  for (const gpu::ShadowView& view : setup.views) {
    ReferenceRaster r = rasterizeReference(scene, view.viewProj, resolution, resolution);
    maps.insert(maps.end(), r.visibility.begin(), r.visibility.end());
  }
  return maps;
}

DirectLightReference directLightReference(const GBufferData& gbuffer, const View& view,
                                          const LightSetup& setup, uint32_t shadowResolution,
                                          std::span<const uint64_t> shadowMaps) {
  if (shadowMaps.size() != setup.views.size() * shadowResolution * shadowResolution)
    throw Error("directLightReference: " + std::to_string(shadowMaps.size()) +
                " shadow-map texels for " + std::to_string(setup.views.size()) + " views of " +
                std::to_string(shadowResolution) + "^2");
  DirectLightReference out;
  out.width = gbuffer.width;
  out.height = gbuffer.height;
  const size_t pixels = size_t{gbuffer.width} * gbuffer.height;
  out.radiance.assign(pixels, glm::dvec3(0.0));
  out.spread.assign(pixels, 0.0);
  out.ambiguous.assign(pixels, 0);
  const glm::dmat4 invViewProj(view.invViewProj);
  const Lighting lighting{setup, static_cast<int>(shadowResolution), shadowMaps};
  for (uint32_t y = 0; y < gbuffer.height; ++y)
    for (uint32_t x = 0; x < gbuffer.width; ++x) {
      const size_t i = size_t{y} * gbuffer.width + x;
      const GBufferSample& s = gbuffer.samples[i];
      if (s.background()) continue;
      glm::dvec2 ndc = glm::dvec2(x + 0.5, y + 0.5) / glm::dvec2(gbuffer.width, gbuffer.height) * 2.0 - 1.0;
      glm::dvec3 origin = unproject(invViewProj, ndc, 0.0);
      glm::dvec3 v = -glm::normalize(unproject(invViewProj, ndc, 0.5) - origin);
      Shading centre = shade(lighting, s, unproject(invViewProj, ndc, s.depth), v);
      out.radiance[i] = centre.radiance;
      out.ambiguous[i] = centre.ambiguous ? 1 : 0;
      // The receiver positions the GPU may have computed: kReceiverDepthUlps either way.
      float lo = s.depth, hi = s.depth;
      for (int k = 0; k < kReceiverDepthUlps; ++k) {
        lo = std::nextafter(lo, 0.0f);
        hi = std::min(std::nextafter(hi, 2.0f), std::nextafter(1.0f, 0.0f));
      }
      for (float z : {lo, hi}) {
        glm::dvec3 d = glm::abs(shade(lighting, s, unproject(invViewProj, ndc, z), v).radiance - centre.radiance);
        out.spread[i] = std::max({out.spread[i], d.x, d.y, d.z});
      }
    }
  return out;
}

}  // namespace engine
