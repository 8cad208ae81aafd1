#include "engine/direct_light_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>

#include "engine/brdf_reference.h"
#include "engine/error.h"
#include "engine/raster_reference.h"
#include "shared/raster.h"

namespace engine {
namespace {

// fp32's unit roundoff and Higham's gamma_n = n u / (1 - n u): an n-term dot product (or n
// chained roundings) evaluated in fp32 errs by at most gamma_n times the sum of |terms|.
constexpr double kUnitRoundoff = 0x1p-24;
constexpr double fp32Gamma(int n) {
  return n * kUnitRoundoff / (1.0 - n * kUnitRoundoff);
}

// BRDF times cosine, and a bound on the error fp32 adds to it beyond a few ulps: GGX's
// d = nh^2 (a2 - 1) + 1 cancels to ~a2 at the lobe's peak, so the roundings of nh (the decoded
// n, h = normalize(v + l), their dot product: ~16) and of d itself (4, absolute) are amplified
// by D's relative derivative 4 nh (1 - a2) / d and by 2 / d. At the peak (d = a2) that bounds
// D's relative error by 0.1 for the glossiest built-in tile (r = 0.08, a2 = 4e-5), 3e-3 for
// r = 0.2 and 1e-5 for the diffuse r = 0.9.
struct Brdf {
  glm::dvec3 value{0.0};
  double error = 0.0;
};

Brdf brdfCos(glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, const GBufferSample& s) {
  double nl = glm::dot(n, l);
  if (nl <= 0.0) return {};
  double alpha = std::max(s.roughness * s.roughness, kMinAlpha);
  double a2 = alpha * alpha;
  double nh = std::max(glm::dot(n, glm::normalize(v + l)), 0.0);
  glm::dvec3 spec = ggxSpecular(n, v, l, s.f0, s.f90, s.roughness);
  double d = nh * nh * (a2 - 1.0) + 1.0;
  double dRelative = (4.0 * nh * (1.0 - a2) * fp32Gamma(16) + 2.0 * fp32Gamma(4)) / d;
  glm::dvec3 specCos = spec * nl;
  return {s.diffuse / std::numbers::pi * nl + specCos,
          std::max({specCos.x, specCos.y, specCos.z}) * dRelative};
}

// unproject() of camera_ray.glsl, with a componentwise bound on the error of its fp32
// evaluation: pixelToNdc's division and subtraction, the four 4-term rows of M (ndc, z, 1),
// the division by w.
struct Point {
  glm::dvec3 p;
  glm::dvec3 error;
};

Point unproject(const glm::dmat4& m, glm::dvec2 ndc, double z) {
  const glm::dvec4 x(ndc, z, 1.0);
  const glm::dvec2 ndcError = fp32Gamma(2) * (glm::abs(ndc) + 1.0);
  const glm::dvec4 h = m * x;
  glm::dvec4 hError;
  for (int j = 0; j < 4; ++j) {
    double terms = 0.0;
    for (int k = 0; k < 4; ++k) terms += std::abs(m[k][j] * x[k]);
    hError[j] =
        fp32Gamma(4) * terms + (std::abs(m[0][j]) * ndcError.x + std::abs(m[1][j]) * ndcError.y);
  }
  Point r;
  r.p = glm::dvec3(h) / h.w;
  r.error = (glm::dvec3(hError) + glm::abs(r.p) * hError.w) / std::abs(h.w) +
            fp32Gamma(1) * glm::abs(r.p);
  return r;
}

// The decision of one shadow-map lookup: the fraction of lit taps, and whether fp32 rounding
// of the lookup itself could change it.
struct Visibility {
  double lit = 1.0;
  bool ambiguous = false;
};

bool nearInteger(double x, double margin) {
  return std::abs(x - std::round(x)) <= margin;
}

// The shader's shadowVisibility(): fraction of the 3x3 texels around q's projection that see
// q. Rounding bounds as unproject(): the clip-space rows of the shadow view's matrix (q itself
// is a sum of fp32 terms, a few more roundings), then the division by w.
Visibility shadowVisibility(const gpu::ShadowView& view, std::span<const uint64_t> map, int size,
                            glm::dvec3 q) {
  const glm::dmat4 m(view.viewProj);
  const glm::dvec4 x(q, 1.0);
  const glm::dvec4 clip = m * x;
  if (clip.w <= 0.0) return {};
  glm::dvec4 clipError;
  for (int j = 0; j < 4; ++j) {
    double terms = 0.0;
    for (int k = 0; k < 4; ++k) terms += std::abs(m[k][j] * x[k]);
    clipError[j] = fp32Gamma(8) * terms;
  }
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  const glm::dvec3 ndcError =
      (glm::dvec3(clipError) + glm::abs(ndc) * clipError.w) / clip.w + fp32Gamma(1) * glm::abs(ndc);
  Visibility r;
  r.ambiguous = std::abs(ndc.z) <= ndcError.z || std::abs(ndc.z - 1.0) <= ndcError.z;
  if (ndc.z < 0.0 || ndc.z > 1.0) return r;
  const double halfSize = 0.5 * size;
  const glm::dvec2 texel = (glm::dvec2(ndc) * 0.5 + 0.5) * static_cast<double>(size);
  // (ndc * 0.5 + 0.5) * size adds two roundings of values up to size.
  r.ambiguous = r.ambiguous || nearInteger(texel.x, halfSize * ndcError.x + fp32Gamma(2) * size) ||
                nearInteger(texel.y, halfSize * ndcError.y + fp32Gamma(2) * size);
  const glm::ivec2 centre(static_cast<int>(std::floor(texel.x)),
                          static_cast<int>(std::floor(texel.y)));
  double lit = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      glm::ivec2 t = glm::clamp(centre + glm::ivec2(dx, dy), glm::ivec2(0), glm::ivec2(size - 1));
      auto hi = static_cast<uint32_t>(map[static_cast<size_t>(t.y) * size + t.x] >> 32);
      if (hi == RASTER_EMPTY_HI) {
        lit += 1.0;
        continue;
      }
      const double stored = std::bit_cast<float>(hi);
      lit += ndc.z <= stored ? 1.0 : 0.0;
      r.ambiguous = r.ambiguous || std::abs(ndc.z - stored) <= ndcError.z;
    }
  r.lit = lit / 9.0;
  return r;
}

// The shader's cubeFace(), plus whether rounding of d = p - light could pick another face.
uint32_t cubeFace(glm::dvec3 d, double dError, bool& ambiguous) {
  glm::dvec3 a = glm::abs(d);
  double sorted[3] = {a.x, a.y, a.z};
  std::sort(sorted, sorted + 3);
  ambiguous = ambiguous || sorted[2] - sorted[1] <= 2.0 * dError;
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y >= 0.0 ? 2u : 3u;
  return d.z >= 0.0 ? 4u : 5u;
}

struct Shading {
  glm::dvec3 radiance{0.0};
  double error = 0.0;              // Brdf::error carried through the light's irradiance
  std::vector<double> visibility;  // per light, the PCF result (1 without shadow views)
  bool ambiguous = false;
};

struct Lighting {
  const LightSetup& setup;
  int shadowResolution;
  std::span<const uint64_t> shadowMaps;
};

// The body of the shader's light loop for receiver p with view vector v.
Shading shade(const Lighting& lighting, const GBufferSample& s, glm::dvec3 p, glm::dvec3 v) {
  Shading out;
  const size_t mapTexels =
      static_cast<size_t>(lighting.shadowResolution) * lighting.shadowResolution;
  for (const gpu::GpuLight& light : lighting.setup.lights) {
    out.visibility.push_back(1.0);
    const LightIncidence incidence = lightIncidence(light, p);
    const glm::dvec3 l = incidence.toLight, irradiance = incidence.irradiance;
    const double distanceToLight = incidence.distance;
    Brdf f = brdfCos(s.normal, v, l, s);
    if (f.value == glm::dvec3(0.0) || irradiance == glm::dvec3(0.0)) continue;
    if (light.info.z > 0u) {
      uint32_t view = light.info.y;
      if (light.info.z == 6u) {
        glm::dvec3 d = p - glm::dvec3(light.position);
        double dError =
            fp32Gamma(1) * glm::length(glm::abs(p) + glm::abs(glm::dvec3(light.position)));
        view += cubeFace(d, dError, out.ambiguous);
      }
      const gpu::ShadowView& shadowView = lighting.setup.views[view];
      double texelWorld = shadowView.texel.x * distanceToLight + shadowView.texel.y;
      glm::dvec3 offset = s.normal * (SHADOW_NORMAL_OFFSET_TEXELS * texelWorld);
      Visibility vis =
          shadowVisibility(shadowView, lighting.shadowMaps.subspan(view * mapTexels, mapTexels),
                           lighting.shadowResolution, p + offset);
      out.visibility.back() = vis.lit;
      out.ambiguous = out.ambiguous || vis.ambiguous;
    }
    out.radiance += f.value * irradiance * out.visibility.back();
    out.error +=
        f.error * std::max({irradiance.x, irradiance.y, irradiance.z}) * out.visibility.back();
  }
  return out;
}

double maxAbsDifference(glm::dvec3 a, glm::dvec3 b) {
  glm::dvec3 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z});
}

// Two unit vectors perpendicular to unit v and to each other.
void tangents(glm::dvec3 v, glm::dvec3& t1, glm::dvec3& t2) {
  t1 = glm::normalize(
      glm::cross(v, std::abs(v.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  t2 = glm::cross(v, t1);
}

}  // namespace

LightIncidence lightIncidence(const gpu::GpuLight& light, glm::dvec3 p) {
  LightIncidence r;
  r.irradiance = glm::dvec3(light.radiance);
  if (light.info.x == LIGHT_DIRECTIONAL) {
    r.toLight = -glm::dvec3(light.direction);
    return r;
  }
  const glm::dvec3 toLight = glm::dvec3(light.position) - p;
  const double d2 = std::max(glm::dot(toLight, toLight), 1e-8);
  r.distance = std::sqrt(d2);
  r.toLight = toLight / r.distance;
  r.irradiance /= d2;
  const double range = light.radiance.w;
  if (range > 0.0) {
    const double x = r.distance / range;
    r.irradiance *= std::clamp(1.0 - x * x * x * x, 0.0, 1.0);
  }
  if (light.info.x == LIGHT_SPOT) {
    const double cd = glm::dot(glm::dvec3(light.direction), -r.toLight);
    const double falloff = std::clamp(cd * light.spot.x + light.spot.y, 0.0, 1.0);
    r.irradiance *= falloff * falloff;
  }
  return r;
}

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
  out.errorBound.assign(pixels, 0.0);
  out.ambiguous.assign(pixels, 0);
  const glm::dmat4 invViewProj(view.invViewProj);
  const Lighting lighting{setup, static_cast<int>(shadowResolution), shadowMaps};
  for (uint32_t y = 0; y < gbuffer.height; ++y)
    for (uint32_t x = 0; x < gbuffer.width; ++x) {
      const size_t i = size_t{y} * gbuffer.width + x;
      const GBufferSample& s = gbuffer.samples[i];
      if (s.background()) continue;
      const glm::dvec2 ndc =
          glm::dvec2(x + 0.5, y + 0.5) / glm::dvec2(gbuffer.width, gbuffer.height) * 2.0 - 1.0;
      const Point receiver = unproject(invViewProj, ndc, s.depth);
      const Point near = unproject(invViewProj, ndc, 0.0), mid = unproject(invViewProj, ndc, 0.5);
      const glm::dvec3 dir = mid.p - near.p;
      const glm::dvec3 v = -glm::normalize(dir);
      // cameraRay()'s direction errs by the two points' errors across their distance, plus
      // the subtraction and normalize roundings.
      const double vError = glm::length(near.error + mid.error) / glm::length(dir) + fp32Gamma(6);

      Shading centre = shade(lighting, s, receiver.p, v);
      out.radiance[i] = s.emission + centre.radiance;
      bool ambiguous = centre.ambiguous;
      // Where the GPU may have put the receiver and the view vector: each position axis and
      // each tangent direction of v, both ways. Their changes add up to a first-order bound of
      // the change anywhere in that box; a shadow decision that flips inside it is ambiguous.
      auto probe = [&](glm::dvec3 p, glm::dvec3 dirToViewer) {
        Shading moved = shade(lighting, s, p, dirToViewer);
        ambiguous = ambiguous || moved.ambiguous || moved.visibility != centre.visibility;
        return maxAbsDifference(moved.radiance, centre.radiance);
      };
      double spread = 0.0;
      for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 step(0.0);
        step[axis] = receiver.error[axis];
        spread += std::max(probe(receiver.p + step, v), probe(receiver.p - step, v));
      }
      glm::dvec3 t1, t2;
      tangents(v, t1, t2);
      for (const glm::dvec3& t : {t1, t2})
        spread += std::max(probe(receiver.p, glm::normalize(v + vError * t)),
                           probe(receiver.p, glm::normalize(v - vError * t)));
      out.errorBound[i] = spread + centre.error;
      out.ambiguous[i] = ambiguous ? 1 : 0;
    }
  return out;
}

}  // namespace engine
