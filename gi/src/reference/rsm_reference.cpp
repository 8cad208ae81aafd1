#include "reference/rsm_reference.h"

#include <algorithm>
#include <cmath>

#include "reference/sg_math.h"

namespace gi {
double luminance709(const glm::dvec3& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

std::vector<RsmTexelReference> rsmFluxReference(const engine::GBufferData& surface,
                                                const RsmView& view, const FluxSource& source) {
  const glm::dmat4 inv(view.invViewProjRelative);
  const glm::dvec3 axis(view.axis);
  const glm::dvec3 radiance(source.radiance);
  const glm::dvec2 falloffParams(source.falloff);
  const double texelArea = view.texelArea;
  std::vector<RsmTexelReference> out(surface.samples.size());
  for (uint32_t y = 0; y < surface.height; ++y) {
    for (uint32_t x = 0; x < surface.width; ++x) {
      const engine::GBufferSample& s = surface.at(x, y);
      RsmTexelReference& t = out[size_t{y} * surface.width + x];
      if (s.background()) continue;
      glm::dvec2 ndc((x + 0.5) / surface.width * 2.0 - 1.0, (y + 0.5) / surface.height * 2.0 - 1.0);
      glm::dvec4 h = inv * glm::dvec4(ndc, static_cast<double>(s.depth), 1.0);
      glm::dvec3 offset = glm::dvec3(h) / h.w;
      if (view.perspective) {
        double c = glm::dot(glm::normalize(offset), axis);
        double falloff = std::clamp(c * falloffParams.x + falloffParams.y, 0.0, 1.0);
        t.incident = radiance * (falloff * falloff * texelArea * c * c * c);
        if (source.range > 0.0f) {
          const double r = glm::length(offset) / source.range;
          t.incident *= std::clamp(1.0 - r * r * r * r, 0.0, 1.0);
        }
      } else {
        t.incident = radiance * texelArea;
      }
      t.lit = luminance709(t.incident) > 0.0 ? 1.0 : 0.0;
      t.offset = offset * t.lit;
      t.diffuseFlux = s.diffuse * t.incident;
      // The specular lobe's directional albedo at the light's incidence (rsm_flux.h).
      const glm::dvec3 toLight = view.perspective ? -glm::normalize(offset) : -axis;
      const double nl = std::max(glm::dot(s.normal, toLight), 1e-4);
      const glm::dvec2 table = ggxSpecularAlbedo(nl, std::max(s.roughness * s.roughness, 1e-3));
      t.specularFlux = (s.f90 * table.x + s.f0 * (table.y - table.x)) * t.incident;
      t.roughness = s.roughness * t.lit;
    }
  }
  return out;
}

double rsmSolidAngleSum(uint32_t size, double halfAngle) {
  const double tanHalf = std::tan(halfAngle);
  const double side = 2.0 * tanHalf / size;  // texel side on the plane at unit distance
  double sum = 0.0;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      double u = ((x + 0.5) / size * 2.0 - 1.0) * tanHalf;
      double v = ((y + 0.5) / size * 2.0 - 1.0) * tanHalf;
      double cosTheta = 1.0 / std::sqrt(1.0 + u * u + v * v);
      sum += side * side * cosTheta * cosTheta * cosTheta;
    }
  }
  return sum;
}

}  // namespace gi
