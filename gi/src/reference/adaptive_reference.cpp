#include "reference/adaptive_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "reference/rsm_reference.h"

namespace gi {
namespace {

struct Surface {
  bool sky = true;
  glm::dvec3 position{0.0};  // relative to the eye
  glm::dvec3 normal{0.0};
  glm::dvec3 albedo{0.0};
  double roughness = 0.0;
  glm::dvec3 f0{0.0};
  double f90 = 0.0;
};

Surface surfaceAt(const engine::GBufferData& g, const gpu::AdaptiveDecidePush& push,
                  glm::uvec2 pixel) {
  const engine::GBufferSample& t = g.at(pixel.x, pixel.y);
  const glm::dvec2 ndc = (glm::dvec2(pixel) + 0.5) / glm::dvec2(push.viewport) * 2.0 - 1.0;
  const glm::dvec4 h = glm::dmat4(push.invViewProjRelative) * glm::dvec4(ndc, t.depth, 1.0);
  return {t.background(), glm::dvec3(h) / h.w, t.normal, t.diffuse, t.roughness, t.f0, t.f90};
}

// adaptive_decide.comp's sameSurface, in double.
bool sameSurface(const Surface& s, const Surface& parent, const gpu::AdaptiveDecidePush& push) {
  const glm::dvec3 f0Change = glm::abs(s.f0 - parent.f0);
  const double f90Change = std::abs(s.f90 - parent.f90);
  return !parent.sky &&
         std::abs(glm::dot(parent.normal, s.position - parent.position)) <=
             push.planeTolerance * glm::length(s.position) &&
         glm::dot(s.normal, parent.normal) >= push.normalCosine &&
         std::abs(s.roughness - parent.roughness) <= push.roughnessTolerance &&
         std::max({f0Change.r, f0Change.g, f0Change.b, f90Change}) <= push.f0Tolerance;
}

}  // namespace

AdaptiveLevel adaptiveLevelReference(const engine::GBufferData& g,
                                     const gpu::AdaptiveDecidePush& push,
                                     const AdaptiveLevel* parents, const AdaptiveShade& shade) {
  const uint32_t level = push.level, parentLevel = level + 1;
  AdaptiveLevel out;
  out.width = gpu::adaptiveLevelSize(push.viewport.x, level);
  out.height = gpu::adaptiveLevelSize(push.viewport.y, level);
  const size_t texels = size_t{out.width} * out.height;
  out.diffuse.assign(texels, glm::dvec3(0.0));
  out.glossy.assign(texels, glm::dvec3(0.0));
  out.origin.assign(texels, 0);
  out.queued.assign(texels, 0);
  out.plain.assign(texels, 0);
  out.exact.assign(texels, 0);
  out.sky.assign(texels, 0);
  const glm::ivec2 parentSize(gpu::adaptiveLevelSize(push.viewport.x, parentLevel),
                              gpu::adaptiveLevelSize(push.viewport.y, parentLevel));
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      const size_t i = out.index({x, y});
      const glm::uvec2 pixel = gpu::adaptiveRepresentative({x, y}, level);
      const Surface s = surfaceAt(g, push, pixel);
      if (s.sky) {
        out.sky[i] = 1;
        continue;
      }
      bool interpolate = level < push.coarsest, reuse = false;
      glm::dvec3 diffuse(0.0), glossy(0.0);
      uint32_t origin = 0;
      if (interpolate) {
        // The parents around the pixel and their bilinear weights, as the shader finds them.
        const glm::ivec2 first(x >> 1, y >> 1);
        const glm::ivec2 last = glm::min(first + 1, parentSize - 1);
        const glm::dvec2 t = glm::clamp(
            (glm::dvec2(pixel) -
             glm::dvec2(gpu::adaptiveRepresentative(glm::uvec2(first), parentLevel))) /
                glm::max(
                    glm::dvec2(gpu::adaptiveRepresentative(glm::uvec2(last - first), parentLevel)),
                    glm::dvec2(1.0)),
            0.0, 1.0);
        double lightMin = std::numeric_limits<double>::infinity(), lightMax = 0.0, lightSum = 0.0,
               largest = -1.0;
        for (uint32_t k = 0; k < 4; ++k) {
          const glm::bvec2 upper((k & 1) != 0, (k & 2) != 0);
          const glm::ivec2 parent(upper.x ? last.x : first.x, upper.y ? last.y : first.y);
          const double w = (upper.x ? t.x : 1.0 - t.x) * (upper.y ? t.y : 1.0 - t.y);
          const Surface p =
              surfaceAt(g, push, gpu::adaptiveRepresentative(glm::uvec2(parent), parentLevel));
          if (!sameSurface(s, p, push)) interpolate = false;
          const size_t j = parents->index(glm::uvec2(parent));
          const double light =
              luminance709(parents->diffuse[j] * s.albedo) + luminance709(parents->glossy[j]);
          lightMin = std::min(lightMin, light);
          lightMax = std::max(lightMax, light);
          lightSum += light;
          diffuse += w * parents->diffuse[j];
          glossy += w * parents->glossy[j];
          if (w > largest) {
            largest = w;
            origin = parents->origin[j];
          }
        }
        if (!(lightMax - lightMin <= push.lightTolerance * 0.25 * lightSum)) interpolate = false;
        // The first parent's light, shaded at this very pixel.
        if (!interpolate && x % 2 == 0 && y % 2 == 0) {
          const size_t j = parents->index(glm::uvec2(first));
          reuse = parents->exact[j] != 0;
          diffuse = parents->diffuse[j];
          glossy = parents->glossy[j];
          origin = parents->origin[j];
        }
      }
      if (!interpolate && !reuse) {
        const IndirectRadiance r = shade(pixel);
        // No glossy term where F0 and F90 read as 0 (non-finite values read as 0).
        bool specular = false;
        for (double v : {s.f0.r, s.f0.g, s.f0.b, s.f90}) specular |= std::isfinite(v) && v != 0.0;
        out.plain[i] = push.splitGlossy != 0 && !specular;
        diffuse = r.diffuse;
        glossy = out.plain[i] ? glm::dvec3(0.0) : r.glossy;
        origin = level;
        out.queued[i] = 1;
      }
      out.exact[i] = !interpolate;
      // A non-finite albedo reads as 0 at level 0, as in the shading.
      glm::dvec3 albedo = s.albedo;
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(albedo[c])) albedo[c] = 0.0;
      out.diffuse[i] = level == 0 ? diffuse * albedo : diffuse;
      out.glossy[i] = glossy;
      out.origin[i] = origin;
    }
  return out;
}

std::vector<AdaptiveLevel> adaptiveShadingReference(const engine::GBufferData& g,
                                                    gpu::AdaptiveDecidePush push,
                                                    const AdaptiveShade& shade) {
  std::vector<AdaptiveLevel> levels(push.coarsest + 1);
  for (uint32_t level = push.coarsest + 1; level-- > 0;) {
    push.level = level;
    levels[level] = adaptiveLevelReference(
        g, push, level < push.coarsest ? &levels[level + 1] : nullptr, shade);
  }
  return levels;
}

}  // namespace gi
