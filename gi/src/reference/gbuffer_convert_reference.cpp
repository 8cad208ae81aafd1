#include "reference/gbuffer_convert_reference.h"

#include <cmath>

#include "shared/gbuffer_convert.h"

namespace gi {

double forwardDepthReference(uint32_t encoding, double stored, glm::dvec4 depthRow) {
  double f = stored;
  if (encoding == GBUFFER_DEPTH_REVERSED_NDC) f = 1.0 - stored;
  if (encoding == GBUFFER_DEPTH_VIEW_DISTANCE) {
    if (!(stored > 0.0) || std::isinf(stored)) return 1.0;
    const double z = -stored;
    f = (depthRow.x * z + depthRow.y) / (depthRow.z * z + depthRow.w);
  }
  return f >= 0.0 && f < 1.0 ? f : 1.0;  // outside [0, 1), non-finite included: the sky
}

glm::dvec2 octahedralReference(uint32_t encoding, glm::dvec4 stored) {
  if (encoding == GBUFFER_NORMAL_OCTAHEDRAL) return glm::dvec2(stored);
  glm::dvec3 n = encoding == GBUFFER_NORMAL_WORLD_UNSIGNED ? glm::dvec3(stored) * 2.0 - 1.0
                                                           : glm::dvec3(stored);
  const double length2 = glm::dot(n, n);
  if (!(length2 > 0.0)) return glm::dvec2(0.0);
  n /= std::sqrt(length2);
  const glm::dvec2 p = glm::dvec2(n) / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
  if (n.z > 0.0) return p;
  const glm::dvec2 sign(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
  return (1.0 - glm::abs(glm::dvec2(p.y, p.x))) * sign;
}

}  // namespace gi
