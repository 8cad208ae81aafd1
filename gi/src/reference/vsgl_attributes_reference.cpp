#include "reference/vsgl_attributes_reference.h"

#include <cmath>

#include "reference/rsm_reference.h"
#include "reference/vsgl_sampling.h"
#include "shared/vsgl.h"

namespace gi {
namespace {

bool finite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

}  // namespace

std::array<std::vector<glm::dvec4>, VSGL_ATTR_COUNT> vsglAttributesReference(
    const RsmImages& rsm, const RsmView& view, bool broadReflections) {
  std::array<std::vector<glm::dvec4>, VSGL_ATTR_COUNT> out;
  for (auto& a : out) a.assign(rsm.position.size(), glm::dvec4(0.0));
  for (size_t i = 0; i < rsm.position.size(); ++i) {
    const glm::vec4 &p = rsm.position[i], &d = rsm.diffuse[i], &s = rsm.specular[i];
    if (!(p.w > 0.0f && finite(p) && finite(d) && finite(s))) continue;
    const glm::dvec3 y(p), n = rsm.surface.samples[i].normal;
    const glm::dvec3 toLight = view.perspective ? -glm::normalize(y) : -glm::dvec3(view.axis);
    const double pdf = luminance709(glm::dvec3(d)) + luminance709(glm::dvec3(s));
    const SgLobe lobe = specularLobe(n, toLight, static_cast<double>(s.a));
    const glm::dvec3 glossy =
        (broadReflections ? glossyShare(lobe.sharpness) : 1.0) * glm::dvec3(s);
    // As the shader: what the glossy lobe does not keep, exactly 0 when it keeps all.
    const glm::dvec3 lambert = glm::dvec3(d) + (glm::dvec3(s) - glossy);
    const double wd = luminance709(lambert), ws = luminance709(glossy);
    const double rs = banerjeeMeanLength(lobe.sharpness);
    const double yy = glm::dot(y, y);
    out[VSGL_ATTR_DIFFUSE_POWER][i] = glm::dvec4(lambert, wd);
    out[VSGL_ATTR_DIFFUSE_POSITION][i] = glm::dvec4(wd * y, wd * yy);
    out[VSGL_ATTR_DIFFUSE_AXIS][i] = glm::dvec4(wd * VSGL_DIFFUSE_LOBE_LENGTH * n, pdf);
    out[VSGL_ATTR_SPECULAR_POWER][i] = glm::dvec4(glossy, ws);
    out[VSGL_ATTR_SPECULAR_POSITION][i] = glm::dvec4(ws * y, ws * yy);
    out[VSGL_ATTR_SPECULAR_AXIS][i] = glm::dvec4(ws * rs * lobe.axis, 0.0);
  }
  return out;
}

}  // namespace gi
