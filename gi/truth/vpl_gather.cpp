#include "vpl_gather.h"

#include <chrono>
#include <cmath>
#include <numbers>

#include "engine/brdf_reference.h"
#include "engine/gbuffer_reference.h"
#include "engine/raster_reference.h"
#include "passes/rsm.h"
#include "pixel_parallel.h"
#include "reference/rsm_reference.h"
#include "shading_point.h"

namespace truth {

namespace {

// The lit texels of one view of light `l`, texel indices within the view.
std::vector<Vpl> rsmViewVpls(const engine::Scene& scene, const EmbreeScene& rays,
                             const engine::Light& l, const gi::RsmView& view, uint32_t rsmSize) {
  const engine::ReferenceRaster raster =
      engine::rasterizeReference(scene, view.raster, rsmSize, rsmSize);
  const engine::GBufferData surface = engine::resolveGBufferReference(
      scene, view.view, raster.visibility, engine::BackFaces::PerMaterial);
  const std::vector<gi::RsmTexelReference> texels =
      gi::rsmFluxReference(surface, view, gi::lightFluxSource(l));
  const glm::dvec3 origin(view.origin), axis(view.axis);
  std::vector<Vpl> vpls;
  for (size_t i = 0; i < texels.size(); ++i) {
    const gi::RsmTexelReference& t = texels[i];
    if (t.lit == 0.0) continue;
    const engine::GBufferSample& s = surface.samples[i];
    Vpl v;
    v.position = origin + t.offset;
    v.normal = s.normal;
    v.geometricNormal = s.normal;
    // The RSM's fp32 depth puts the texel's point up to ~1e-4 of the light's range off its
    // surface, more than a ray offset can clear: a third of the Cornell box's VPLs at 32^2 sat
    // below their surface and shadowed themselves (the gather read 10 % low). The light's ray
    // through the point finds the surface the texel saw; the VPL moves onto it, in double.
    const glm::dvec3 dir = view.perspective ? glm::normalize(t.offset) : axis;
    const glm::dvec3 start = view.perspective ? origin : v.position - dir * glm::dot(t.offset, dir);
    if (const RayHit hit = rays.intersect(start, dir); hit.hit) {
      const ShadingPoint snapped =
          shadingPoint(scene, hit, start, dir, engine::BackFaces::PerMaterial);
      v.position = snapped.position;
      v.geometricNormal = snapped.geometricNormal;
    }
    v.incident = t.incident;
    v.diffuse = s.diffuse;
    v.f0 = s.f0;
    v.f90 = s.f90;
    v.roughness = s.roughness;
    v.texel = static_cast<uint32_t>(i);
    // The texel's patch: its solid angle from the light (texelArea cos^3 on the unit-distance
    // plane, as the flux) times t^2 / cos at the surface; a parallel beam's texelArea / cos.
    double cosine;
    if (view.perspective) {
      const double t2 = glm::dot(t.offset, t.offset);
      v.toLight = -t.offset / std::sqrt(t2);
      const double c = glm::dot(-v.toLight, axis);
      cosine = std::abs(glm::dot(v.normal, v.toLight));
      v.area = view.texelArea * c * c * c * t2 / std::max(cosine, 1e-6);
    } else {
      v.toLight = -axis;
      cosine = std::abs(glm::dot(v.normal, v.toLight));
      v.area = view.texelArea / std::max(cosine, 1e-6);
    }
    vpls.push_back(v);
  }
  return vpls;
}

}  // namespace

std::vector<Vpl> rsmVpls(const engine::Scene& scene, const EmbreeScene& rays, uint32_t light,
                         uint32_t rsmSize) {
  const engine::Light& l = scene.lights.at(light);
  std::vector<Vpl> vpls;
  const std::vector<gi::RsmView> views = gi::makeRsmViews(scene.bounds(), l, rsmSize);
  for (size_t face = 0; face < views.size(); ++face) {
    std::vector<Vpl> own = rsmViewVpls(scene, rays, l, views[face], rsmSize);
    for (Vpl& v : own) v.texel += static_cast<uint32_t>(face * size_t{rsmSize} * rsmSize);
    vpls.insert(vpls.end(), own.begin(), own.end());
  }
  return vpls;
}

std::vector<Vpl> rsmVpls(const engine::Scene& scene, const EmbreeScene& rays,
                         std::span<const uint32_t> lights, uint32_t rsmSize) {
  std::vector<Vpl> vpls;
  size_t firstView = 0;
  for (uint32_t light : lights) {
    std::vector<Vpl> own = rsmVpls(scene, rays, light, rsmSize);
    for (Vpl& v : own) v.texel += static_cast<uint32_t>(firstView * rsmSize * rsmSize);
    vpls.insert(vpls.end(), own.begin(), own.end());
    firstView += gi::makeRsmViews(scene.bounds(), scene.lights.at(light), rsmSize).size();
  }
  return vpls;
}

VplGatherImage vplGather(const engine::Scene& scene, const EmbreeScene& rays,
                         const engine::View& view, const std::vector<Vpl>& vpls, unsigned threads,
                         bool visibility) {
  const auto start = std::chrono::steady_clock::now();
  VplGatherImage image;
  image.width = view.width;
  image.height = view.height;
  const size_t pixels = size_t{view.width} * view.height;
  image.diffuse.assign(pixels, glm::dvec3(0.0));
  image.glossy.assign(pixels, glm::dvec3(0.0));
  image.vplCount = vpls.size();
  forEachPixel(pixels, threadCount(threads), [&](size_t i) {
    const std::optional<PrimaryHit> primary = primaryHit(scene, rays, view, i);
    if (!primary) return;
    const engine::CameraRay& ray = primary->ray;
    const ShadingPoint& x = primary->point;
    const engine::GBufferSample& s = x.surface;
    const glm::dvec3 v = -ray.dir;
    const glm::dvec3 xo = offsetOrigin(x.position, x.geometricNormal);
    glm::dvec3 diffuse(0.0), glossy(0.0);
    for (const Vpl& vpl : vpls) {
      const glm::dvec3 toVpl = vpl.position - x.position;
      const double d2 = glm::dot(toVpl, toVpl);
      const double d = std::sqrt(d2);
      if (d <= 0.0) continue;
      const glm::dvec3 w = toVpl / d;  // x -> VPL
      const double cosX = glm::dot(s.normal, w), cosY = glm::dot(vpl.normal, -w);
      if (cosX <= 0.0 || cosY <= 0.0 || glm::dot(x.geometricNormal, w) <= 0.0) continue;
      // Both ends off their surfaces (the VPL lies on one): x's offset point to the VPL's,
      // lifted along its normal towards x's side.
      if (visibility && !rays.visible(xo, offsetOrigin(vpl.position, vpl.geometricNormal)))
        continue;
      if (glm::dot(vpl.normal, vpl.toLight) <= 0.0) continue;  // lit from behind its normal
      // Both GGX lobes, the VPL's and the receiver's, widened by the patch's angular size seen
      // from x (path regularisation, Kaplanyan and Dachsbacher 2013): a point sample of a
      // near-mirror lobe (the checker's alpha = 0.0064) would otherwise flash wherever one VPL
      // happens to align, at either end; the widening vanishes as the RSM is refined, so the
      // gather still converges.
      const double spread = vpl.area / (4.0 * std::numbers::pi * d2);
      const auto widened = [spread](double roughness) {
        const double alpha = std::max(roughness * roughness, engine::kMinAlpha);
        return std::sqrt(std::sqrt(alpha * alpha + spread));  // back to GGX's perceptual roughness
      };
      const glm::dvec3 fy =
          vpl.diffuse / std::numbers::pi +
          engine::ggxSpecular(vpl.normal, -w, vpl.toLight, vpl.f0, vpl.f90, widened(vpl.roughness));
      // Intensity towards x: the patch's radiance f_y E, E = Phi_in / A (Phi_in already holds
      // the light's cosine), times A cos_y.
      const glm::dvec3 intensity = fy * vpl.incident * cosY;
      const glm::dvec3 arriving = intensity / (d2 + vpl.area / std::numbers::pi);
      diffuse += s.diffuse / std::numbers::pi * cosX * arriving;
      glossy +=
          engine::ggxSpecular(s.normal, v, w, s.f0, s.f90, widened(s.roughness)) * cosX * arriving;
    }
    image.diffuse[i] = diffuse;
    image.glossy[i] = glossy;
  });
  image.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace truth
