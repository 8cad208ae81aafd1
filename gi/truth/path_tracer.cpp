#include "path_tracer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <thread>

#include "engine/brdf_reference.h"
#include "engine/direct_light.h"
#include "engine/direct_light_reference.h"
#include "engine/error.h"
#include "engine/gbuffer_reference.h"
#include "engine/orthonormal_basis.h"
#include "mirror_planes.h"
#include "pixel_parallel.h"
#include "reference/rsm_reference.h"
#include "shading_point.h"

namespace truth {
namespace {

constexpr double kPi = std::numbers::pi;

// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation"), XSH RR output; one stream per pixel.
class Pcg32 {
 public:
  Pcg32(uint64_t seed, uint64_t stream) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  double uniform() { return next() * 0x1p-32; }  // [0, 1)

 private:
  uint64_t state_ = 0;
  uint64_t inc_;
};

// A local frame around unit n: z = n.
struct Frame {
  glm::dvec3 t, b, n;
  explicit Frame(glm::dvec3 normal) : n(normal) {
    const engine::OrthonormalBasis basis = engine::orthonormalBasis(n);
    t = basis.tangent;
    b = basis.bitangent;
  }
  glm::dvec3 toLocal(glm::dvec3 w) const {
    return {glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)};
  }
  glm::dvec3 toWorld(glm::dvec3 w) const { return w.x * t + w.y * b + w.z * n; }
};

// The GGX alpha and n . v floors of brdf.glsl (engine/brdf_reference.h).
double ggxAlpha(double roughness) {
  return std::max(roughness * roughness, engine::kMinAlpha);
}

// Heitz 2018, Listing 1: a visible normal of the GGX with roughness alpha for the local view v.
glm::dvec3 sampleVisibleNormal(glm::dvec3 v, double alpha, double u1, double u2) {
  const glm::dvec3 vh = glm::normalize(glm::dvec3(alpha * v.x, alpha * v.y, v.z));
  const double lensq = vh.x * vh.x + vh.y * vh.y;
  const glm::dvec3 t1 =
      lensq > 0.0 ? glm::dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lensq) : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 t2 = glm::cross(vh, t1);
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  const double p1 = r * std::cos(phi);
  const double s = 0.5 * (1.0 + vh.z);
  const double p2 = (1.0 - s) * std::sqrt(std::max(1.0 - p1 * p1, 0.0)) + s * r * std::sin(phi);
  const glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(1.0 - p1 * p1 - p2 * p2, 0.0)) * vh;
  return glm::normalize(glm::dvec3(alpha * nh.x, alpha * nh.y, std::max(nh.z, 0.0)));
}

// pdf of the reflected direction l when h is a visible normal: G1(v) D(h) / (4 n.v)
// (Heitz 2018, Eq. 3 and the reflection Jacobian 1 / (4 v.h)).
double visibleNormalReflectionPdf(glm::dvec3 v, glm::dvec3 l, double alpha) {
  const double a2 = alpha * alpha;
  const glm::dvec3 h = glm::normalize(v + l);
  const double nv = v.z;
  const double g1 = 2.0 * nv / (nv + std::sqrt(a2 + (1.0 - a2) * nv * nv));
  return g1 * engine::ggxD(h.z, a2) / (4.0 * nv);
}

// Radiance that `light` reflects at `at` towards `toViewer`, with an exact shadow ray; each
// lobe apart (Lambert, GGX).
struct Reflected {
  glm::dvec3 diffuse{0.0};
  glm::dvec3 glossy{0.0};
};

Reflected reflectLight(const EmbreeScene& rays, const gpu::GpuLight& light, const ShadingPoint& at,
                       glm::dvec3 toViewer, bool shadowRay = true) {
  const engine::LightIncidence incidence = engine::lightIncidence(light, at.position);
  const glm::dvec3 l = incidence.toLight;
  const double nl = glm::dot(at.surface.normal, l);
  if (nl <= 0.0 || incidence.irradiance == glm::dvec3(0.0)) return {};
  // A light behind the triangle itself is shadowed by it, whatever the shading normal says.
  if (shadowRay && glm::dot(at.geometricNormal, l) <= 0.0) return {};
  if (shadowRay) {
    // The segment ends at the light itself (measured from the offset origin: a tfar measured
    // from the surface point would reach past a light that sits on a surface).
    const glm::dvec3 from = offsetOrigin(at.position, at.geometricNormal);
    const bool lit = incidence.distance > 0.0
                         ? rays.visible(from, glm::dvec3(light.position))
                         : !rays.occluded(from, l, 0.0, std::numeric_limits<double>::infinity());
    if (!lit) return {};
  }
  const engine::GBufferSample& s = at.surface;
  Reflected r;
  r.diffuse = s.diffuse / kPi * nl * incidence.irradiance;
  r.glossy = engine::ggxSpecular(s.normal, toViewer, l, s.f0, s.f90, s.roughness) * nl *
             incidence.irradiance;
  return r;
}

// x's BRDF sampling, fixed per pixel: the mixture of cosine and GGX visible-normal sampling, in x's
// frame.
struct Lobes {
  Frame frame;
  glm::dvec3 v;
  double alpha;
  double pSpecular;
  Lobes(const engine::GBufferSample& s, glm::dvec3 view)
      : frame(s.normal), v(frame.toLocal(view)), alpha(ggxAlpha(s.roughness)) {
    // Lobe choice in proportion to the lobes' weights, kept in [0.1, 0.9] so that neither
    // starves; cosine sampling only when the view grazes the shading normal.
    const double dw = gi::luminance709(s.diffuse), sw = gi::luminance709(s.f0);
    pSpecular = dw + sw > 0.0 ? std::clamp(sw / (dw + sw), 0.1, 0.9) : 0.5;
    if (v.z <= engine::kMinNv) pSpecular = 0.0;
  }
  // Solid-angle density of a local direction l.
  double pdf(glm::dvec3 l) const {
    if (l.z <= 0.0) return 0.0;
    return (pSpecular > 0.0 ? pSpecular * visibleNormalReflectionPdf(v, l, alpha) : 0.0) +
           (1.0 - pSpecular) * l.z / kPi;
  }
};

// Per-pixel running sums of the indirect estimate.
// Strategy (c) at x for one light: the mirror planes whose reflection of the light x can see,
// each picked with probability share / their count, in place of (a)'s direction.
struct MirrorStrategy {
  std::vector<MirrorLobe> lobes;
  double share = 0.0;
};

struct PixelState {
  bool background = true;
  ShadingPoint x{};
  glm::dvec3 view{0.0};
  Lobes lobes{engine::GBufferSample{}, glm::dvec3(0.0, 0.0, 1.0)};  // set with x in pass 1
  // Strategy (c) for each bouncing light (MirrorStrategy), set with x in pass 1.
  std::vector<struct MirrorStrategy> mirrors;
  glm::dvec3 direct{0.0};
  glm::dvec3 diffuseSum{0.0};
  glm::dvec3 glossySum{0.0};
  double luminanceSum = 0.0;
  double luminanceSquares = 0.0;
  uint32_t samples = 0;
  Pcg32 rng{0, 0};  // seeded from (seed, pixel) in pass 1
};

// Where the bouncing light sends its rays for the light-sampling strategy: a spot's cone or a
// point light's sphere (directions uniform in solid angle) or, for a directional light, a disc
// across the light covering the scene's bounding sphere (origins uniform in area).
struct LightSampler {
  glm::dvec3 position{0.0};  // spot, point
  glm::dvec3 axis{0.0};      // the way light travels
  bool directional = false;
  double cosOuter = 1.0;   // spot; -1 for a point light
  glm::dvec3 centre{0.0};  // directional: the disc's centre, upstream of the scene
  double radius = 0.0;     // directional
  double pdf = 0.0;        // per steradian (spot) or per m^2 across the beam (directional)

  LightSampler(const engine::Light& light, const engine::Bounds& bounds) {
    axis = glm::normalize(glm::dvec3(light.direction));
    if (light.type == engine::LightType::Directional) {
      directional = true;
      const glm::dvec3 mid = 0.5 * (glm::dvec3(bounds.min) + glm::dvec3(bounds.max));
      radius = 0.5 * glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min)) + 1e-3;
      centre = mid - 2.0 * radius * axis;
      pdf = 1.0 / (kPi * radius * radius);
    } else {
      position = glm::dvec3(light.position);
      // A point light sends rays over the whole sphere: the cone of half angle pi.
      cosOuter = light.type == engine::LightType::Spot
                     ? std::cos(static_cast<double>(light.outerConeAngle))
                     : -1.0;
      pdf = 1.0 / (2.0 * kPi * (1.0 - cosOuter));
    }
  }

  // A ray leaving the light; `u1`, `u2` uniform.
  std::pair<glm::dvec3, glm::dvec3> sample(double u1, double u2) const {
    const Frame frame(axis);
    const double phi = 2.0 * kPi * u2;
    if (directional) {
      const double r = radius * std::sqrt(u1);
      return {centre + frame.toWorld({r * std::cos(phi), r * std::sin(phi), 0.0}), axis};
    }
    const double c = 1.0 - u1 * (1.0 - cosOuter);
    const double s = std::sqrt(std::max(1.0 - c * c, 0.0));
    return {position, frame.toWorld({s * std::cos(phi), s * std::sin(phi), c})};
  }

  // The density, per m^2 of surface, with which sample() lands first on point p whose
  // geometric normal is ng (0 outside the cone).
  double areaPdf(glm::dvec3 p, glm::dvec3 ng) const {
    if (directional) return pdf * std::abs(glm::dot(ng, axis));
    const glm::dvec3 d = p - position;
    const double t2 = glm::dot(d, d);
    const glm::dvec3 w = d / std::sqrt(t2);
    if (glm::dot(w, axis) < cosOuter) return 0.0;
    return pdf * std::abs(glm::dot(ng, w)) / t2;
  }
};

// The one-bounce estimator at a pixel's visible point x, its strategies for the bounce point y
// combined by the balance heuristic (Veach 1997, section 9.2): (a) a direction from x's BRDF
// sampling, y the first hit, the light at y by a shadow ray; (b) a ray from the light, y its
// first hit, connected to x by a visibility ray; (c) y near a mirror plane's reflection of the
// light (MirrorLobe), reached by a ray from x like (a). (a) handles y close to x (corners), where
// (b)'s 1/d^2 explodes; (b) finds a small lit area that (a) rarely hits; (c) the caustic of a
// near-mirror y, which both miss. (a) and (c) are one sample of their mixture, so a sample traces
// no more rays than with (a) alone.
class Tracer {
 public:
  Tracer(const engine::Scene& scene, const EmbreeScene& rays, const gpu::GpuLight& bouncing,
         const engine::Light& light)
      : scene_(scene),
        rays_(rays),
        bouncing_(bouncing),
        lightSampler_(light, scene.bounds()),
        mirrorLight_(mirrorLight(light)),
        mirrorPlanes_(findMirrorPlanes(scene)),
        minHeight_(1e-6 * glm::length(glm::dvec3(scene.bounds().max - scene.bounds().min))) {}

  // Strategy (c)'s lobes at x for this light (mirrorLobe says which planes qualify); none when
  // `mirrors` is off.
  MirrorStrategy mirrorsAt(const PixelState& px, bool mirrors) const {
    MirrorStrategy m;
    for (size_t k = 0; mirrors && k < mirrorPlanes_.planes.size(); ++k)
      if (const std::optional<MirrorLobe> lobe = mirrorLobe(
              mirrorPlanes_, static_cast<int32_t>(k), px.x.position, mirrorLight_, minHeight_))
        m.lobes.push_back(*lobe);
    m.share = m.lobes.empty() ? 0.0 : kMirrorShare;
    return m;
  }

  struct Contribution {
    glm::dvec3 diffuse{0.0};
    glm::dvec3 glossy{0.0};
  };

  // One estimate of this light's one-bounce radiance at x: (a) or (c), and (b).
  Contribution estimate(PixelState& px, const MirrorStrategy& m) const {
    const Lobes& lobes = px.lobes;
    Pcg32& rng = px.rng;
    const double u[5] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
    Contribution c = receiverStrategy(px, m, lobes, u[0], u[1], u[2]);
    const Contribution b = lightStrategy(px, m, lobes, u[3], u[4]);
    c.diffuse += b.diffuse;
    c.glossy += b.glossy;
    return c;
  }

 private:
  // The share of strategy (c) in the mixture with (a) where x has mirror lobes (on the checker
  // at 160x90 the samples per pixel varied by 10 % between shares of 0.3 and 0.7).
  static constexpr double kMirrorShare = 0.5;

  // x's lobes times the radiance `incoming` from world direction `dir`, times `scale`.
  static Contribution atX(const PixelState& px, glm::dvec3 dir, glm::dvec3 incoming, double scale) {
    const engine::GBufferSample& s = px.x.surface;
    const double cosine = glm::dot(s.normal, dir);
    Contribution c;
    if (cosine <= 0.0) return c;
    c.diffuse = s.diffuse / kPi * cosine * incoming * scale;
    c.glossy = engine::ggxSpecular(s.normal, px.view, dir, s.f0, s.f90, s.roughness) * cosine *
               incoming * scale;
    return c;
  }

  // The density per m^2 with which the mixture of (a) and (c) reaches y on `triangle` along the
  // world direction `dir` from x; `geometry` = |cos_y| / d^2 turns (a)'s solid angle into area.
  static double receiverAreaPdf(const MirrorStrategy& m, const Lobes& lobes, glm::dvec3 dir,
                                uint32_t triangle, glm::dvec3 y, double geometry,
                                const MirrorPlanes& planes) {
    double area = (1.0 - m.share) * lobes.pdf(lobes.frame.toLocal(dir)) * geometry;
    const int32_t plane = planes.ofTriangle[triangle];
    if (plane < 0) return area;
    for (const MirrorLobe& lobe : m.lobes)
      if (lobe.plane == plane) area += m.share / static_cast<double>(m.lobes.size()) * lobe.pdf(y);
    return area;
  }

  // A direction from x's mixture of (a) and (c), in world space, and the plane (c) aimed at (-1
  // for (a)).
  struct ReceiverSample {
    glm::dvec3 dir;
    int32_t plane;
  };
  ReceiverSample receiverDirection(const PixelState& px, const MirrorStrategy& m,
                                   const Lobes& lobes, double u0, double u1, double u2) const {
    if (u0 < m.share) {
      const size_t count = m.lobes.size();
      const size_t k =
          std::min(count - 1, static_cast<size_t>(u0 / m.share * static_cast<double>(count)));
      const MirrorLobe& lobe = m.lobes[k];
      return {glm::normalize(lobe.sample(u1, u2) - px.x.position), lobe.plane};
    }
    u0 = (u0 - m.share) / (1.0 - m.share);
    glm::dvec3 l;
    if (u0 < lobes.pSpecular) {
      const glm::dvec3 h = sampleVisibleNormal(lobes.v, lobes.alpha, u1, u2);
      l = 2.0 * glm::dot(lobes.v, h) * h - lobes.v;
    } else {
      const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
      l = glm::dvec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0 - u1, 0.0)));
    }
    return {lobes.frame.toWorld(l), -1};
  }

  Contribution receiverStrategy(const PixelState& px, const MirrorStrategy& m, const Lobes& lobes,
                                double u0, double u1, double u2) const {
    const auto [dir, plane] = receiverDirection(px, m, lobes, u0, u1, u2);
    // Directions below x's shading normal carry nothing to x; into its own triangle they would
    // leak through it.
    if (glm::dot(px.x.surface.normal, dir) <= 0.0 || glm::dot(px.x.geometricNormal, dir) <= 0.0)
      return {};
    const RayHit hit = rays_.intersect(offsetOrigin(px.x.position, px.x.geometricNormal), dir);
    // (c) samples points of its plane: a ray that meets anything else first is no sample of it
    // (receiverAreaPdf gives (c) no density there).
    if (!hit.hit || (plane >= 0 && mirrorPlanes_.ofTriangle[hit.triangle] != plane)) return {};
    // y bounces the light on the side x sees (reflectLight shadows the rest), so the back face
    // x sees is the one the light would see.
    const ShadingPoint y =
        shadingPoint(scene_, hit, px.x.position, dir, engine::BackFaces::PerMaterial);
    const Reflected r = reflectLight(rays_, bouncing_, y, -dir);
    if (r.diffuse + r.glossy == glm::dvec3(0.0)) return {};
    // The two sides' densities of y per m^2.
    const double geometry = std::abs(glm::dot(y.geometricNormal, dir)) / (hit.t * hit.t);
    const double areaX =
        receiverAreaPdf(m, lobes, dir, hit.triangle, y.position, geometry, mirrorPlanes_);
    const double areaB = lightSampler_.areaPdf(y.position, y.geometricNormal);
    if (areaX <= 0.0) return {};
    return atX(px, dir, r.diffuse + r.glossy, geometry / (areaX + areaB));
  }

  Contribution lightStrategy(const PixelState& px, const MirrorStrategy& m, const Lobes& lobes,
                             double u1, double u2) const {
    const auto [origin, dir] = lightSampler_.sample(u1, u2);
    const RayHit hit = rays_.intersect(origin, dir);
    if (!hit.hit) return {};
    const ShadingPoint y =  // normal faces the light
        shadingPoint(scene_, hit, origin, dir, engine::BackFaces::PerMaterial);
    const glm::dvec3 toX = px.x.position - y.position;
    const double d2 = glm::dot(toX, toX);
    if (d2 <= 0.0) return {};
    const double d = std::sqrt(d2);
    const glm::dvec3 w = toX / d;  // y -> x
    // x on y's lit side, y in front of x's own triangle, nothing in between.
    if (glm::dot(y.geometricNormal, w) <= 0.0 || glm::dot(px.x.geometricNormal, -w) <= 0.0)
      return {};
    const engine::LightIncidence incidence = engine::lightIncidence(bouncing_, y.position);
    const double nl = glm::dot(y.surface.normal, incidence.toLight);
    if (nl <= 0.0 || incidence.irradiance == glm::dvec3(0.0)) return {};
    // Both ends off their surfaces: a segment measured from x itself would reach past y into
    // y's own surface (measured: strategy (b) lost 80 % of the Cornell ceiling's light).
    if (!rays_.visible(offsetOrigin(px.x.position, px.x.geometricNormal),
                       offsetOrigin(y.position, y.geometricNormal)))
      return {};
    const engine::GBufferSample& s = y.surface;
    const glm::dvec3 radiance =
        (s.diffuse / kPi +
         engine::ggxSpecular(s.normal, w, incidence.toLight, s.f0, s.f90, s.roughness)) *
        nl * incidence.irradiance;
    const double areaB = lightSampler_.areaPdf(y.position, y.geometricNormal);
    const double geometry = std::abs(glm::dot(y.geometricNormal, w)) / d2;
    const double areaX =
        receiverAreaPdf(m, lobes, -w, hit.triangle, y.position, geometry, mirrorPlanes_);
    if (areaB <= 0.0) return {};
    return atX(px, -w, radiance, geometry / (areaX + areaB));
  }

  const engine::Scene& scene_;
  const EmbreeScene& rays_;
  const gpu::GpuLight& bouncing_;
  LightSampler lightSampler_;
  MirrorLight mirrorLight_;
  MirrorPlanes mirrorPlanes_;
  double minHeight_;  // x closer than this to a mirror plane lies on it
};

double standardError(const PixelState& px) {
  if (px.samples < 2) return std::numeric_limits<double>::infinity();
  const double n = px.samples;
  const double variance =
      std::max(px.luminanceSquares - px.luminanceSum * px.luminanceSum / n, 0.0) / (n - 1.0);
  return std::sqrt(variance / n);
}

}  // namespace

PathTraceImage pathTrace(const engine::Scene& scene, const EmbreeScene& rays,
                         const engine::View& view, uint32_t bouncingLight,
                         const PathTraceSettings& settings) {
  return pathTrace(scene, rays, view, std::span<const uint32_t>(&bouncingLight, 1), settings);
}

PathTraceImage pathTrace(const engine::Scene& scene, const EmbreeScene& rays,
                         const engine::View& view, std::span<const uint32_t> bouncingLights,
                         const PathTraceSettings& settings) {
  for (uint32_t l : bouncingLights)
    if (l >= scene.lights.size())
      throw engine::Error("pathTrace: light " + std::to_string(l) + " of " +
                          std::to_string(scene.lights.size()));
  const auto start = std::chrono::steady_clock::now();
  engine::DirectLightSettings lightSettings;
  lightSettings.shadows = false;  // exact shadow rays instead of maps
  const std::vector<gpu::GpuLight> lights = engine::buildLightSetup(scene, lightSettings).lights;
  std::vector<Tracer> tracers;
  for (uint32_t l : bouncingLights) tracers.emplace_back(scene, rays, lights[l], scene.lights[l]);
  const unsigned threads = threadCount(settings.threads);
  const size_t pixels = size_t{view.width} * view.height;
  std::vector<PixelState> state(pixels);

  // One sample is the sum of every bouncing light's estimate (each with its own strategies).
  auto run = [&](PixelState& px, uint32_t count) {
    for (uint32_t k = 0; k < count; ++k) {
      glm::dvec3 diffuse(0.0), glossy(0.0);
      for (size_t t = 0; t < tracers.size(); ++t) {
        const Tracer::Contribution c = tracers[t].estimate(px, px.mirrors[t]);
        diffuse += c.diffuse;
        glossy += c.glossy;
      }
      px.diffuseSum += diffuse;
      px.glossySum += glossy;
      const double y = gi::luminance709(diffuse + glossy);
      px.luminanceSum += y;
      px.luminanceSquares += y * y;
      ++px.samples;
    }
  };

  // Pass 1: the visible point, the direct light, a pilot of minSamples of the indirect light.
  forEachPixel(pixels, threads, [&](size_t i) {
    PixelState& px = state[i];
    const auto x = static_cast<uint32_t>(i % view.width), y = static_cast<uint32_t>(i / view.width);
    const engine::CameraRay ray = engine::cameraRayReference(view, glm::dvec2(x + 0.5, y + 0.5));
    const RayHit hit = rays.intersect(ray.origin, ray.dir);
    if (!hit.hit) return;
    px.background = false;
    px.x = shadingPoint(scene, hit, ray.origin, ray.dir);
    px.view = -ray.dir;
    px.lobes = Lobes(px.x.surface, px.view);
    for (const Tracer& tracer : tracers)
      px.mirrors.push_back(tracer.mirrorsAt(px, settings.mirrorSampling));
    px.direct = px.x.surface.emission;  // glTF emission, which the host's frame adds too
    for (const gpu::GpuLight& light : lights) {
      const Reflected r = reflectLight(rays, light, px.x, px.view, settings.directShadows);
      px.direct += r.diffuse + r.glossy;
    }
    px.rng = Pcg32(settings.seed, i);
    run(px, settings.minSamples);
  });

  double luminanceTotal = 0.0;
  size_t foreground = 0;
  for (const PixelState& px : state)
    if (!px.background) {
      luminanceTotal += px.luminanceSum / px.samples;
      ++foreground;
    }
  PathTraceImage image;
  image.noiseFloor = foreground > 0 ? settings.relativeError * settings.floorFraction *
                                          luminanceTotal / static_cast<double>(foreground)
                                    : 0.0;

  // Pass 2: each pixel's sample count, from its pilot variance, then that many fresh samples.
  // The pilot only sizes the run and is then dropped: a count decided from the very samples it
  // averages would bias the mean (a pixel whose rare, bright paths had not shown up yet would
  // look converged at a too-low value; measured: -16 % on the analytic wall with BRDF sampling
  // alone), while a count fixed beforehand keeps the mean unbiased.
  std::atomic<size_t> done{0};
  std::atomic<bool> finished{false};
  std::thread reporter;
  if (settings.progress)
    reporter = std::thread([&] {
      auto last = std::chrono::steady_clock::now();
      while (!finished) {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        if (std::chrono::steady_clock::now() - last < std::chrono::seconds(5)) continue;
        last = std::chrono::steady_clock::now();
        std::fprintf(stderr, "path tracer: %.1f %% of pixels done\n",
                     100.0 * static_cast<double>(done) / static_cast<double>(pixels));
      }
    });
  std::vector<double> ratios(pixels, -1.0);  // final standard error / target, per pixel
  forEachPixel(pixels, threads, [&](size_t i) {
    PixelState& px = state[i];
    if (!px.background) {
      // Two sizing runs, then the final one, each started afresh so that no decision rests on
      // the samples the image keeps: the pilot sizes a second run at a quarter of what it
      // predicts, and that run, with several times the pilot's samples, sizes the final one,
      // since a pilot of a few hundred samples can miss the rare paths that carry a pixel's
      // variance. (How much the second run helps has not been measured against one sizing
      // run: a count aimed exactly at the target leaves about half the pixels slightly above
      // it either way, so the image reports the ratio's percentiles instead.)
      double target = 0.0;
      for (const double share : {0.25, 1.0}) {
        const double mean = px.luminanceSum / px.samples;
        target = std::max(settings.relativeError * mean, image.noiseFloor);
        const double error = standardError(px);
        // standard error ~ 1 / sqrt(n): n = this n (error / target)^2.
        const double wanted = target > 0.0 ? px.samples * (error / target) * (error / target)
                                           : double(settings.minSamples);
        const auto count = static_cast<uint32_t>(std::clamp(
            std::ceil(share * wanted), double(settings.minSamples), double(settings.maxSamples)));
        px.diffuseSum = px.glossySum = glm::dvec3(0.0);
        px.luminanceSum = px.luminanceSquares = 0.0;
        px.samples = 0;
        run(px, count);
      }
      ratios[i] = target > 0.0 ? standardError(px) / target : 0.0;
    }
    ++done;
  });
  finished = true;
  if (reporter.joinable()) reporter.join();

  image.width = view.width;
  image.height = view.height;
  image.direct.resize(pixels);
  image.diffuse.resize(pixels);
  image.glossy.resize(pixels);
  image.standardError.resize(pixels);
  image.samples.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const PixelState& px = state[i];
    if (px.background) continue;
    image.direct[i] = px.direct;
    image.diffuse[i] = px.diffuseSum / double(px.samples);
    image.glossy[i] = px.glossySum / double(px.samples);
    image.standardError[i] = standardError(px);
    image.samples[i] = px.samples;
  }
  std::erase_if(ratios, [](double r) { return r < 0.0; });
  std::sort(ratios.begin(), ratios.end());
  if (!ratios.empty()) {
    image.medianErrorRatio = ratios[ratios.size() / 2];
    image.p95ErrorRatio = ratios[std::min(ratios.size() - 1, ratios.size() * 95 / 100)];
  }
  image.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace truth

namespace truth {

PathTraceImage cachedPathTrace(const ReferenceCache& cache, const engine::Scene& scene,
                               const engine::View& view, uint32_t bouncingLight,
                               const PathTraceSettings& settings, bool* fromCache) {
  return cachedPathTrace(cache, scene, view, std::span<const uint32_t>(&bouncingLight, 1), settings,
                         fromCache);
}

PathTraceImage cachedPathTrace(const ReferenceCache& cache, const engine::Scene& scene,
                               const engine::View& view, std::span<const uint32_t> bouncingLights,
                               const PathTraceSettings& settings, bool* fromCache) {
  CacheKey key;
  key.add(scene).add(view);
  // One light keys as before several could bounce (the stored references stay valid).
  for (uint32_t l : bouncingLights) key.add(l);
  if (bouncingLights.size() != 1) key.add(uint32_t(bouncingLights.size()) | 0x80000000u);
  key.add(settings.relativeError).add(settings.floorFraction).add(settings.minSamples);
  key.add(settings.maxSamples).add(settings.seed).add(settings.directShadows);
  key.add(settings.mirrorSampling);
  // Channels: direct, diffuse, glossy (3 each), standard error, samples.
  constexpr uint32_t kChannels = 11;
  const ReferenceCache::EntryLock hold(cache, "pathtrace", key);  // one tracer per reference
  if (std::optional<CachedImage> c = cache.load("pathtrace", key);
      c && c->channels == kChannels && c->scalars.size() == 4) {
    if (fromCache) *fromCache = true;
    PathTraceImage image;
    image.width = c->width;
    image.height = c->height;
    const size_t n = size_t{c->width} * c->height;
    auto channel = [&](uint32_t k) { return c->values.begin() + static_cast<ptrdiff_t>(k * n); };
    auto rgb = [&](uint32_t first, std::vector<glm::dvec3>& out) {
      out.resize(n);
      for (size_t i = 0; i < n; ++i)
        out[i] = glm::dvec3(channel(first)[i], channel(first + 1)[i], channel(first + 2)[i]);
    };
    rgb(0, image.direct);
    rgb(3, image.diffuse);
    rgb(6, image.glossy);
    image.standardError.assign(channel(9), channel(10));
    image.samples.assign(channel(10), channel(11));
    image.noiseFloor = c->scalars[0];
    image.medianErrorRatio = c->scalars[1];
    image.p95ErrorRatio = c->scalars[2];
    image.seconds = c->scalars[3];
    return image;
  }
  if (fromCache) *fromCache = false;
  const EmbreeScene rays(scene);
  PathTraceImage image = pathTrace(scene, rays, view, bouncingLights, settings);
  CachedImage c;
  c.width = image.width;
  c.height = image.height;
  c.channels = kChannels;
  const size_t n = size_t{image.width} * image.height;
  c.values.reserve(n * kChannels);
  for (const std::vector<glm::dvec3>* rgb : {&image.direct, &image.diffuse, &image.glossy})
    for (int k = 0; k < 3; ++k)
      for (const glm::dvec3& v : *rgb) c.values.push_back(v[k]);
  c.values.insert(c.values.end(), image.standardError.begin(), image.standardError.end());
  for (uint32_t s : image.samples) c.values.push_back(s);
  c.scalars = {image.noiseFloor, image.medianErrorRatio, image.p95ErrorRatio, image.seconds};
  cache.store("pathtrace", key, c);
  return image;
}

}  // namespace truth
