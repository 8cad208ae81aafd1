#include "error_budget.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "engine/brdf_reference.h"
#include "engine/gbuffer_reference.h"
#include "engine/orthonormal_basis.h"
#include "pixel_parallel.h"
#include "reference/ism_reference.h"
#include "reference/sg_math.h"
#include "reference/vsgl_emitter.h"
#include "reference/vsgl_shade_reference.h"
#include "shading_point.h"

namespace truth {

namespace {

constexpr double kPi = std::numbers::pi;

double luminance(glm::dvec3 c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// Calls visit(texel, weight) for every level-0 texel under the trilinear fetch at centre x
// (in [0, 1]^2) and level `level` of a size^2 pyramid, as vsgl_generate.comp filters.
template <class Visit>
void forEachKernelTexel(glm::dvec2 x, double level, uint32_t size, Visit visit) {
  const int top = std::countr_zero(size);
  level = std::clamp(level, 0.0, double(top));
  const int l0 = int(std::floor(level)), l1 = std::min(l0 + 1, top);
  const double f = level - l0;
  for (const auto& [l, levelWeight] : {std::pair{l0, 1.0 - f}, std::pair{l1, f}}) {
    if (levelWeight <= 0.0) continue;
    const int n = int(size) >> l, side = 1 << l;
    const glm::dvec2 t = x * double(n) - 0.5;
    const glm::dvec2 base = glm::floor(t), fr = t - base;
    const glm::ivec2 i0 = glm::clamp(glm::ivec2(base), glm::ivec2(0), glm::ivec2(n - 1));
    const glm::ivec2 i1 = glm::clamp(glm::ivec2(base) + 1, glm::ivec2(0), glm::ivec2(n - 1));
    const std::tuple<glm::ivec2, double> corners[] = {{i0, (1.0 - fr.x) * (1.0 - fr.y)},
                                                      {{i1.x, i0.y}, fr.x * (1.0 - fr.y)},
                                                      {{i0.x, i1.y}, (1.0 - fr.x) * fr.y},
                                                      {i1, fr.x * fr.y}};
    for (const auto& [c, w] : corners) {
      if (w <= 0.0) continue;
      const double perTexel = levelWeight * w / double(side * side);
      for (int yy = c.y * side; yy < (c.y + 1) * side; ++yy)
        for (int xx = c.x * side; xx < (c.x + 1) * side; ++xx)
          visit(size_t(yy) * size + size_t(xx), perTexel);
    }
  }
}

// The VPL's reflected power, diffuse + specular luminance, as the module's RSM flux has it
// (rsm_flux.h: the specular lobe's directional albedo at the light's incidence).
double vplPower(const Vpl& v) {
  const double nl = std::max(glm::dot(v.normal, v.toLight), 1e-4);
  const glm::dvec2 table =
      gi::ggxSpecularAlbedo(nl, std::max(v.roughness * v.roughness, engine::kMinAlpha));
  const glm::dvec3 specular = v.f90 * table.x + v.f0 * (table.y - table.x);
  return luminance((v.diffuse + specular) * v.incident);
}

// The i-th of m points of a Fibonacci lattice in [0, 1)^2, shifted by `rotation` (toroidally).
glm::dvec2 latticePoint(uint32_t i, uint32_t m, glm::dvec2 rotation) {
  const double golden = 0.6180339887498949;
  return glm::fract(glm::dvec2((i + 0.5) / m, std::fmod(i * golden, 1.0)) + rotation);
}

// A per-(pixel, lobe) shift of the lattice, so that neighbouring pixels do not share its
// structure; deterministic (no state).
glm::dvec2 rotationFor(uint64_t key) {
  uint64_t z = key + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return glm::dvec2(double(z >> 40) / double(1ull << 24), double(z & 0xFFFFFF) / double(1 << 24));
}

glm::dvec3 fromBasis(glm::dvec3 axis, double cosine, double phi) {
  const engine::OrthonormalBasis b = engine::orthonormalBasis(axis);
  const double s = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
  return s * std::cos(phi) * b.tangent + s * std::sin(phi) * b.bitangent + cosine * axis;
}

// A direction with density proportional to G(w; axis, lambda) (the vMF), from u in [0, 1)^2.
glm::dvec3 sampleSg(glm::dvec3 axis, double lambda, glm::dvec2 u) {
  const double cosine =
      lambda < 1e-6 ? 1.0 - 2.0 * u.x : 1.0 + std::log1p(u.x * std::expm1(-2.0 * lambda)) / lambda;
  return fromBasis(axis, std::clamp(cosine, -1.0, 1.0), 2.0 * kPi * u.y);
}

// The receiver's GGX reflection directions (half vectors with density D(h) (n . h)), and their
// density over outgoing directions D(h) (n . h) / (4 |v . h|).
glm::dvec3 sampleGgx(glm::dvec3 n, glm::dvec3 v, double a2, glm::dvec2 u) {
  const double cos2 = (1.0 - u.x) / (1.0 + (a2 - 1.0) * u.x);
  const glm::dvec3 h = fromBasis(n, std::sqrt(std::max(cos2, 0.0)), 2.0 * kPi * u.y);
  return 2.0 * glm::dot(v, h) * h - v;
}

double ggxDensity(glm::dvec3 n, glm::dvec3 v, double a2, glm::dvec3 w) {
  const glm::dvec3 h = glm::normalize(v + w);
  const double nh = glm::dot(n, h), vh = std::abs(glm::dot(v, h));
  if (nh <= 0.0 || vh <= 0.0) return 0.0;
  return engine::ggxD(nh, a2) * nh / (4.0 * vh);
}

struct Radiance {
  glm::dvec3 diffuse{0.0};
  glm::dvec3 glossy{0.0};
};

// Integral of the lobe's incoming radiance L(w) = scale e^(l) G(w; axis, lambda) against the
// receiver's true BRDF and cosine: half the samples from the SG, half from the GGX lobe
// (balance heuristic, Veach 1997 Eq. 9.13 with counts).
Radiance integrateLobe(const gi::VsglIncomingRadiance& lobe, const gi::ShadeReceiver& r,
                       bool glossy, uint32_t samples, uint64_t key) {
  Radiance out;
  const double amplitude = std::exp(lobe.sg.logAmplitude);
  if (!(amplitude > 0.0) || lobe.scale == glm::dvec3(0.0)) return out;
  const double lambda = lobe.sg.sharpness;
  const glm::dvec3 axis = lobe.sg.axis;
  const double integral = gi::sgIntegral(lambda);
  const double alpha = std::max(r.roughness * r.roughness, engine::kMinAlpha);
  const double a2 = alpha * alpha;
  const bool specular = glossy && (r.f0 != glm::dvec3(0.0) || r.f90 > 0.0);
  const uint32_t fromGgx = specular ? samples / 2 : 0, fromSg = samples - fromGgx;
  const glm::dvec2 rotation = rotationFor(key);
  for (uint32_t j = 0; j < samples; ++j) {
    const bool sg = j < fromSg;
    const glm::dvec2 u =
        sg ? latticePoint(j, fromSg, rotation) : latticePoint(j - fromSg, fromGgx, rotation);
    const glm::dvec3 w = sg ? sampleSg(axis, lambda, u) : sampleGgx(r.normal, r.view, a2, u);
    const double cosine = glm::dot(r.normal, w);
    if (cosine <= 0.0) continue;
    const double g = gi::sgEvaluate(w, axis, lambda);
    const double density =
        fromSg * g / integral + (specular ? fromGgx * ggxDensity(r.normal, r.view, a2, w) : 0.0);
    if (!(density > 0.0) || g == 0.0) continue;
    const glm::dvec3 arriving = lobe.scale * (amplitude * g * cosine / density);
    out.diffuse += r.albedo / kPi * arriving;
    if (glossy)
      out.glossy += engine::ggxSpecular(r.normal, r.view, w, r.f0, r.f90, r.roughness) * arriving;
  }
  return out;
}

// The texels of every view the kernels or the VPLs lie in.
size_t texelCount(const std::vector<gpu::Vsgl>& vsgls, const KernelLayout& layout,
                  const std::vector<Vpl>& vpls) {
  size_t texels = size_t{layout.rsmSize} * layout.rsmSize;
  for (size_t k = 0; k < vsgls.size(); ++k)
    texels = std::max(texels, layout.firstTexel(k) + size_t{layout.rsmSize} * layout.rsmSize);
  for (const Vpl& v : vpls) texels = std::max(texels, size_t{v.texel} + 1);
  return texels;
}

// Per VSGL, the VPLs under its kernel (indices into `vpls`) with their kernel weight times
// power; empty for k-means clusters.
std::vector<std::vector<std::pair<uint32_t, double>>> kernelMembers(
    const std::vector<gpu::Vsgl>& vsgls, const KernelLayout& layout, const std::vector<Vpl>& vpls) {
  std::vector<int64_t> vplAt(texelCount(vsgls, layout, vpls), -1);
  for (size_t j = 0; j < vpls.size(); ++j) vplAt.at(vpls[j].texel) = int64_t(j);
  std::vector<std::vector<std::pair<uint32_t, double>>> members(vsgls.size());
  for (size_t k = 0; k < vsgls.size(); ++k) {
    const gpu::Vsgl& v = vsgls[k];
    if (v.kernel.z < 0.0f) continue;
    const size_t first = layout.firstTexel(k);
    std::map<uint32_t, double> weights;  // a texel is reached once per level and corner
    forEachKernelTexel(glm::dvec2(v.kernel.x, v.kernel.y), v.kernel.z, layout.rsmSize,
                       [&](size_t t, double w) {
                         if (vplAt[first + t] >= 0) weights[uint32_t(vplAt[first + t])] += w;
                       });
    for (const auto& [j, w] : weights)
      if (const double p = w * vplPower(vpls[j]); p > 0.0) members[k].push_back({j, p});
  }
  return members;
}

}  // namespace

bool flatVsgl(const gpu::Vsgl& vsgl) {
  return vsgl.diffuse.power.a > 0.0f && gi::vsglPlanarity(vsgl.diffuse.axisSharpness.w) >= 0.95;
}

std::vector<double> kernelTexelWeights(const std::vector<gpu::Vsgl>& vsgls,
                                       const KernelLayout& layout, const std::vector<Vpl>& vpls) {
  const size_t texels = texelCount(vsgls, layout, vpls);
  for (const gpu::Vsgl& v : vsgls)
    if (v.kernel.z < 0.0f) return std::vector<double>(texels, 1.0);  // k-means: a partition
  std::vector<double> power(texels, 0.0);
  for (const Vpl& v : vpls) power.at(v.texel) = vplPower(v);
  std::vector<double> weights(texels, 0.0);
  for (size_t i = 0; i < vsgls.size(); ++i) {
    const gpu::Vsgl& v = vsgls[i];
    const glm::dvec2 x(v.kernel.x, v.kernel.y);
    const double level = v.kernel.z;
    const size_t first = layout.firstTexel(i);
    double covered = 0.0;  // the kernel-weighted power of the texels under it
    forEachKernelTexel(x, level, layout.rsmSize,
                       [&](size_t t, double k) { covered += k * power[first + t]; });
    const double total = double(v.diffuse.power.a) + double(v.specular.power.a);
    if (!(covered > 0.0) || !(total > 0.0)) continue;
    const double scale = total / covered;
    forEachKernelTexel(x, level, layout.rsmSize,
                       [&](size_t t, double k) { weights[first + t] += scale * k; });
  }
  return weights;
}

std::vector<Vpl> weightedVpls(const std::vector<Vpl>& vpls, const std::vector<double>& weights) {
  std::vector<Vpl> out;
  out.reserve(vpls.size());
  for (Vpl v : vpls) {
    v.incident *= weights.at(v.texel);
    if (v.incident != glm::dvec3(0.0)) out.push_back(v);
  }
  return out;
}

VsglStageImages vsglStages(const engine::Scene& scene, const EmbreeScene& rays,
                           const engine::View& view, const std::vector<gpu::Vsgl>& vsgls,
                           const VsglStageSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const size_t pixels = size_t{view.width} * view.height;
  VsglStageImages out;
  out.numeric.assign(pixels, glm::dvec3(0.0));
  out.unshadowed.assign(pixels, glm::dvec3(0.0));
  out.unshadowedFlat.assign(pixels, glm::dvec3(0.0));
  out.analytic.assign(pixels, glm::dvec3(0.0));
  const std::vector<Vpl>* vpls = settings.kernelVpls;
  std::vector<std::vector<std::pair<uint32_t, double>>> members;
  if (vpls) {
    out.areaVisible.assign(pixels, glm::dvec3(0.0));
    members = kernelMembers(vsgls, settings.kernels, *vpls);
  }
  std::vector<gi::IsmFrameReference> frames;
  std::vector<gi::VsglEmission> emissions;
  for (const gpu::Vsgl& v : vsgls) {
    frames.push_back(gi::ismFrameReference(v, settings.ismCentreOffset));
    emissions.push_back(gi::vsglEmission(v, settings.planarEmitters));
  }
  forEachPixel(pixels, threadCount(settings.threads), [&](size_t i) {
    const std::optional<PrimaryHit> primary = primaryHit(scene, rays, view, i);
    if (!primary) return;
    const engine::CameraRay& ray = primary->ray;
    const ShadingPoint& x = primary->point;
    gi::ShadeReceiver r;
    r.position = x.position;
    r.normal = x.surface.normal;
    r.view = -ray.dir;
    r.albedo = x.surface.diffuse;
    r.f0 = x.surface.f0;
    r.f90 = x.surface.f90;
    r.roughness = x.surface.roughness;
    const glm::dvec3 xo = offsetOrigin(x.position, x.geometricNormal);
    std::vector<double> visible(vsgls.size(), 0.0);
    for (size_t k = 0; k < vsgls.size(); ++k)
      visible[k] = frames[k].lit && rays.visible(frames[k].centre, xo) ? 1.0 : 0.0;
    // Area visibility: each VPL's ray is cast once per receiver, when a kernel first needs it.
    std::vector<double> areaVisible;
    if (vpls) {
      areaVisible = visible;
      std::vector<int8_t> vplVisible(vpls->size(), -1);
      for (size_t k = 0; k < vsgls.size(); ++k) {
        double seen = 0.0, all = 0.0;
        for (const auto& [j, weight] : members[k]) {
          const Vpl& y = (*vpls)[j];
          const glm::dvec3 d = x.position - y.position;
          const double d2 = glm::dot(d, d);
          const glm::dvec3 w = d / std::sqrt(d2);
          const double transfer = std::max(glm::dot(y.normal, w), 0.0) *
                                  std::max(-glm::dot(r.normal, w), 0.0) / (d2 + y.area / kPi);
          if (!(transfer > 0.0)) continue;
          if (vplVisible[j] < 0)
            vplVisible[j] = rays.visible(offsetOrigin(y.position, y.geometricNormal), xo);
          all += weight * transfer;
          seen += weight * transfer * vplVisible[j];
        }
        if (all > 0.0) areaVisible[k] = seen / all;
      }
    }
    const gi::IndirectRadiance analytic = gi::shadeReference(
        r, vsgls, settings.glossy, settings.planarEmitters, [&](uint32_t k) { return visible[k]; });
    out.analytic[i] = analytic.diffuse + analytic.glossy;
    Radiance numeric, unshadowed, flat, area;
    for (size_t k = 0; k < vsgls.size(); ++k) {
      const bool isFlat = flatVsgl(vsgls[k]);
      const auto lobes = {std::pair{&vsgls[k].diffuse, &emissions[k].diffuse},
                          std::pair{&vsgls[k].specular, &emissions[k].specular}};
      uint64_t lobeIndex = 0;
      for (const auto& [lobe, emission] : lobes) {
        ++lobeIndex;
        if (std::max({lobe->power.r, lobe->power.g, lobe->power.b}) <= 0.0f) continue;
        const gi::VsglIncomingRadiance incoming =
            gi::vsglIncomingRadiance(*lobe, r.position, *emission, r.normal);
        const Radiance l = integrateLobe(incoming, r, settings.glossy, settings.samplesPerLobe,
                                         (uint64_t(i) * vsgls.size() + k) * 2 + lobeIndex);
        unshadowed.diffuse += l.diffuse;
        unshadowed.glossy += l.glossy;
        numeric.diffuse += visible[k] * l.diffuse;
        numeric.glossy += visible[k] * l.glossy;
        if (isFlat) {
          flat.diffuse += l.diffuse;
          flat.glossy += l.glossy;
        }
        if (vpls) {
          area.diffuse += areaVisible[k] * l.diffuse;
          area.glossy += areaVisible[k] * l.glossy;
        }
      }
    }
    out.numeric[i] = numeric.diffuse + numeric.glossy;
    out.unshadowed[i] = unshadowed.diffuse + unshadowed.glossy;
    out.unshadowedFlat[i] = flat.diffuse + flat.glossy;
    if (vpls) out.areaVisible[i] = area.diffuse + area.glossy;
  });
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::vector<BudgetRegion> budgetRegions(const engine::Scene& scene, const EmbreeScene& rays,
                                        const engine::View& view, const std::vector<Vpl>& vpls) {
  const engine::Bounds b = scene.bounds();
  const double diagonal = glm::length(glm::dvec3(b.max) - glm::dvec3(b.min));
  // The emitting planes: VPLs grouped by their plane (normal to 1e-3, offset to 1e-3 of the
  // diagonal); those holding at least 1 % of the power count.
  struct Plane {
    glm::dvec3 normal;
    double offset;
    double power;
  };
  std::map<std::tuple<long, long, long, long>, Plane> planes;
  double totalPower = 0.0;
  for (const Vpl& v : vpls) {
    const glm::dvec3 n = v.geometricNormal;
    const double offset = glm::dot(n, v.position);
    const auto key = std::make_tuple(std::lround(n.x * 1e3), std::lround(n.y * 1e3),
                                     std::lround(n.z * 1e3), std::lround(offset / diagonal * 1e3));
    Plane& p = planes.try_emplace(key, Plane{n, offset, 0.0}).first->second;
    p.power += vplPower(v);
    totalPower += vplPower(v);
  }
  std::vector<Plane> emitting;
  for (const auto& [key, p] : planes)
    if (p.power >= 0.01 * totalPower) emitting.push_back(p);

  const size_t pixels = size_t{view.width} * view.height;
  std::vector<BudgetRegion> regions(pixels, BudgetRegion::Background);
  forEachPixel(pixels, threadCount(0), [&](size_t i) {
    const std::optional<PrimaryHit> primary = primaryHit(scene, rays, view, i);
    if (!primary) return;
    const ShadingPoint& x = primary->point;
    const glm::dvec3 n = x.geometricNormal;
    // Another surface within reach along the tangent plane (tilted up by 5 degrees so that the
    // receiver's own plane is never hit): a contact line, whatever plane the receiver is on.
    const engine::OrthonormalBasis basis = engine::orthonormalBasis(n);
    const glm::dvec3 origin = offsetOrigin(x.position, n);
    const double reach = 0.03 * diagonal;
    for (int k = 0; k < 8; ++k) {
      const double phi = 2.0 * kPi * k / 8.0;
      const glm::dvec3 dir = glm::normalize(std::cos(phi) * basis.tangent +
                                            std::sin(phi) * basis.bitangent + 0.0875 * n);
      if (rays.occluded(origin, dir, 0.0, reach)) {
        regions[i] = BudgetRegion::Contact;
        return;
      }
    }
    for (const Plane& p : emitting)
      if (glm::dot(n, p.normal) > 0.999 &&
          std::abs(glm::dot(p.normal, x.position) - p.offset) < 2e-3 * diagonal) {
        regions[i] = BudgetRegion::Coplanar;
        return;
      }
    regions[i] = BudgetRegion::Rest;
  });
  return regions;
}

}  // namespace truth
