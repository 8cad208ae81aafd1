#include "reference/env_fis_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "reference/env_paraboloid.h"

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;
// brdf.glsl's floors.
constexpr double kMinAlpha = 1e-3;
constexpr double kMinNv = 1e-4;

// common/brdf.glsl's smithGgxCorrelatedV: G2 / (4 nl nv), height-correlated Smith.
double smithGgxCorrelatedV(double nv, double nl, double a2) {
  const double gv = nl * std::sqrt(nv * nv * (1.0 - a2) + a2);
  const double gl = nv * std::sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / std::max(gv + gl, 1e-12);
}

glm::dvec3 schlickFresnel(glm::dvec3 f0, double f90, double vh) {
  const double m = 1.0 - vh, m2 = m * m;
  return f0 + (glm::dvec3(f90) - f0) * (m2 * m2 * m);
}

double fract(double x) {
  return x - std::floor(x);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The map

glm::dvec3 envMapBilinear(const EnvMapReference& map, uint32_t layer, glm::dvec2 st,
                          uint32_t level) {
  const int n = static_cast<int>(map.levelSize(level));
  const glm::dvec2 p = st * double(n) - 0.5;
  const glm::dvec2 p0 = glm::floor(p);
  const glm::dvec2 f = p - p0;
  const auto clampIndex = [n](double i) {
    return static_cast<uint32_t>(std::clamp(static_cast<int>(i), 0, n - 1));
  };
  const uint32_t x0 = clampIndex(p0.x), x1 = clampIndex(p0.x + 1.0);
  const uint32_t y0 = clampIndex(p0.y), y1 = clampIndex(p0.y + 1.0);
  const glm::dvec3 top =
      map.texel(level, layer, x0, y0) * (1.0 - f.x) + map.texel(level, layer, x1, y0) * f.x;
  const glm::dvec3 bottom =
      map.texel(level, layer, x0, y1) * (1.0 - f.x) + map.texel(level, layer, x1, y1) * f.x;
  return top * (1.0 - f.y) + bottom * f.y;
}

glm::dvec3 envMapTrilinear(const EnvMapReference& map, uint32_t layer, glm::dvec2 st,
                           double level) {
  const double top = double(envMapLevelCount(map) - 1);
  const double d = std::clamp(level, 0.0, top);  // also maps +inf to the coarsest level
  const double d0 = std::floor(d);
  const double f = d - d0;
  const auto l0 = static_cast<uint32_t>(d0);
  const uint32_t l1 = std::min(l0 + 1, envMapLevelCount(map) - 1);
  const glm::dvec3 a = envMapBilinear(map, layer, st, l0);
  if (f == 0.0) return a;
  return a * (1.0 - f) + envMapBilinear(map, layer, st, l1) * f;
}

glm::dvec3 envMapLookup(const EnvMapReference& map, glm::dvec3 direction, double level) {
  const ParaboloidCoordinates c = paraboloidFromDirection(direction);
  return envMapTrilinear(map, c.map, c.st, level);
}

// ---------------------------------------------------------------------------------------------
// Receivers

double envFisGgxAlpha(double roughness) {
  return std::max(roughness * roughness, kMinAlpha);
}

glm::dvec3 envFisTangent(glm::dvec3 normal) {
  const glm::dvec3 axis =
      std::abs(normal.y) > 0.999 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  return glm::normalize(glm::cross(axis, normal));
}

EnvFisReceiver envFisReceiverFromMaterial(glm::dvec3 normal, glm::dvec3 view, glm::dvec3 albedo,
                                          double roughness, glm::dvec3 f0, double f90,
                                          EnvFisBrdf brdf, double wardAnisotropy) {
  EnvFisReceiver r;
  r.normal = normal;
  r.view = view;
  r.albedo = albedo;
  r.f0 = f0;
  r.f90 = f90;
  r.brdf = brdf;
  r.roughness = roughness;
  const double alpha = envFisGgxAlpha(roughness);
  r.phongExponent = 2.0 / (alpha * alpha) - 2.0;
  r.wardAlphaX = alpha;
  r.wardAlphaY = alpha * wardAnisotropy;
  r.tangent = envFisTangent(normal);
  return r;
}

uint32_t envFisHash(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

glm::dvec2 envFisRotation(glm::uvec2 pixel) {
  const uint32_t a = envFisHash(pixel.x + envFisHash(pixel.y));
  const uint32_t b = envFisHash(a);
  return glm::dvec2(double(a >> 8u), double(b >> 8u)) * 0x1p-24;
}

// ---------------------------------------------------------------------------------------------
// Lobe samples

EnvLobeSample envFisSampleLobe(const EnvFisReceiver& r, glm::dvec2 u) {
  EnvLobeSample s;
  const glm::dvec3 n = r.normal, v = r.view;
  switch (r.brdf) {
    case EnvFisBrdf::Ggx: {
      const double alpha = envFisGgxAlpha(r.roughness), a2 = alpha * alpha;
      const LobeFrame frame = lobeFrame(n);
      const glm::dvec3 hLocal = sampleGgxHalfVector(u, alpha);
      const glm::dvec3 h = frame.toWorld(hLocal);
      const double vh = glm::dot(v, h);
      s.direction = reflectAbout(v, h);
      s.pdf = std::abs(vh) > 0.0 ? ggxHalfVectorPdf(hLocal, alpha) / (4.0 * std::abs(vh)) : 0.0;
      const double nl = glm::dot(n, s.direction);
      const double nh = hLocal.z;
      if (nl <= 0.0 || vh <= 0.0 || !(nh > 0.0)) break;
      const double nv = std::max(glm::dot(n, v), kMinNv);
      // w = F 4 V nl (v . h) / (n . h): D V F nl / (D (n . h) / (4 v . h)).
      s.weight =
          schlickFresnel(r.f0, r.f90, vh) * (4.0 * smithGgxCorrelatedV(nv, nl, a2) * nl * vh / nh);
      break;
    }
    case EnvFisBrdf::Phong: {
      const glm::dvec3 mirror = reflectAbout(v, n);
      s.direction = samplePhong(u, mirror, r.phongExponent);
      s.pdf = phongPdf(s.direction, mirror, r.phongExponent);
      if (glm::dot(n, s.direction) > 0.0) s.weight = r.f0;
      break;
    }
    case EnvFisBrdf::Ward: {
      const LobeFrame frame = lobeFrame(n, r.tangent);
      const glm::dvec3 hLocal = sampleWardHalfVector(u, r.wardAlphaX, r.wardAlphaY);
      const glm::dvec3 h = frame.toWorld(hLocal);
      const double vh = std::abs(glm::dot(v, h));
      s.direction = reflectAbout(v, h);
      s.pdf = vh > 0.0 ? wardHalfVectorPdf(hLocal, r.wardAlphaX, r.wardAlphaY) / (4.0 * vh) : 0.0;
      if (glm::dot(n, s.direction) > 0.0 && s.pdf > 0.0) s.weight = r.f0;
      break;
    }
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Shading

EnvShading envFisShade(const EnvFisReceiver& receiver, const EnvMapReference& map, const ShRgb& sh,
                       const EnvFisSettings& settings) {
  EnvShading out;
  // E clamped at 0: nine SH terms ring negative opposite a bright, small source.
  out.diffuse =
      receiver.albedo / kPi * glm::max(shIrradiance(sh, receiver.normal), glm::dvec3(0.0));
  const uint32_t count = settings.sampleCount;
  const glm::dvec2 offset =
      settings.mode == EnvFisMode::Randomised ? envFisRotation(settings.pixel) : glm::dvec2(0.0);
  glm::dvec3 sum(0.0);
  for (uint32_t k = 0; k < count; ++k) {
    glm::dvec2 u = hammersleyPoint(k, count);
    if (settings.mode == EnvFisMode::Randomised) u = {fract(u.x + offset.x), fract(u.y + offset.y)};
    const EnvLobeSample s = envFisSampleLobe(receiver, u);
    if (s.weight == glm::dvec3(0.0)) continue;
    double level = 0.0;
    if (settings.mode == EnvFisMode::Filtered) {
      const double r = paraboloidSolidAnglePerArea(std::abs(s.direction.z));
      level = fisMipLevel(s.pdf, r, count, map.size, map.size, settings.kernelExtent);
    }
    sum += s.weight * envMapLookup(map, s.direction, level);
  }
  out.glossy = sum / double(count);
  return out;
}

EnvReferenceShading envMonteCarloReference(const EnvFisReceiver& receiver,
                                           const EnvRadianceFunction& radiance,
                                           uint32_t glossyStrata, uint32_t diffuseStrata,
                                           uint64_t seed) {
  // A 64-bit LCG (Knuth's MMIX constants), 53 bits per variate: the same jitter with every
  // standard library, unlike std's distributions.
  uint64_t state = seed;
  const auto jitter = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * 0x1p-53;
  };
  // The mean of one sample per stratum, and the stratified estimator's standard error from
  // pairs of neighbouring strata (a, b): E[(f_a - f_b)^2] = s_a^2 + s_b^2 + (m_a - m_b)^2 >=
  // s_a^2 + s_b^2, so sum over pairs of (f_a - f_b)^2 / M^2 bounds Var(mean) = sum s_i^2 / M^2
  // from above (the "collapsed strata" estimate; tight where neighbouring means are close).
  struct Moments {
    glm::dvec3 sum{0.0}, pairs2{0.0};
    double count = 0.0;
    void addPair(glm::dvec3 a, glm::dvec3 b) {
      sum += a + b;
      pairs2 += (a - b) * (a - b);
      count += 2.0;
    }
    glm::dvec3 mean() const { return sum / count; }
    glm::dvec3 stdError() const { return glm::sqrt(pairs2) / count; }
  };
  const auto stratum = [&](uint32_t i, uint32_t j, uint32_t m) {
    // Jittered stratum (i, j) of m x m, kept inside [0, 1) (u1 = 1 is GGX's horizon pole).
    const double x = (i + jitter()) / m, y = (j + jitter()) / m;
    return glm::dvec2(std::min(x, 1.0 - 0x1p-53), std::min(y, 1.0 - 0x1p-53));
  };
  EnvReferenceShading out;
  const auto glossySample = [&](uint32_t i, uint32_t j, uint32_t m) {
    const EnvLobeSample s = envFisSampleLobe(receiver, stratum(i, j, m));
    return s.weight == glm::dvec3(0.0) ? glm::dvec3(0.0) : s.weight * radiance(s.direction);
  };
  const LobeFrame frame = lobeFrame(receiver.normal);
  const auto diffuseSample = [&](uint32_t i, uint32_t j, uint32_t m) {
    // Cosine-weighted: pdf = cos / pi, so albedo / pi cos / pdf = albedo.
    const glm::dvec2 u = stratum(i, j, m);
    const double sinTheta = std::sqrt(u.x), cosTheta = std::sqrt(1.0 - u.x);
    const double phi = 2.0 * kPi * u.y;
    const glm::dvec3 l =
        frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
    return receiver.albedo * radiance(l);
  };
  // Strata in pairs along a row: an odd count is rounded up.
  const uint32_t mg = glossyStrata + (glossyStrata & 1u), md = diffuseStrata + (diffuseStrata & 1u);
  Moments glossy, diffuse;
  for (uint32_t j = 0; j < mg; ++j)
    for (uint32_t i = 0; i < mg; i += 2) {
      const glm::dvec3 a = glossySample(i, j, mg);
      glossy.addPair(a, glossySample(i + 1, j, mg));
    }
  for (uint32_t j = 0; j < md; ++j)
    for (uint32_t i = 0; i < md; i += 2) {
      const glm::dvec3 a = diffuseSample(i, j, md);
      diffuse.addPair(a, diffuseSample(i + 1, j, md));
    }
  out.value.glossy = glossy.mean();
  out.glossyStdError = glossy.stdError();
  out.value.diffuse = diffuse.mean();
  out.diffuseStdError = diffuse.stdError();
  return out;
}

}  // namespace gi
