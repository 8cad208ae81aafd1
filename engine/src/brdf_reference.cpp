#include "engine/brdf_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace engine {

double ggxD(double nh, double a2) {
  double d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (std::numbers::pi * d * d);
}

double smithGgxCorrelatedV(double nv, double nl, double a2) {
  double gv = nl * std::sqrt(nv * nv * (1.0 - a2) + a2);
  double gl = nv * std::sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / std::max(gv + gl, 1e-12);
}

glm::dvec3 schlickFresnel(glm::dvec3 f0, double f90, double vh) {
  double m = 1.0 - vh;
  return f0 + (f90 - f0) * std::pow(m, 5.0);
}

glm::dvec3 ggxSpecular(glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, glm::dvec3 f0, double f90,
                       double roughness) {
  const double nl = glm::dot(n, l);
  if (nl <= 0.0) return glm::dvec3(0.0);
  const double nv = std::max(glm::dot(n, v), kMinNv);
  const double alpha = std::max(roughness * roughness, kMinAlpha);
  const double a2 = alpha * alpha;
  const glm::dvec3 h = glm::normalize(v + l);
  return ggxD(std::max(glm::dot(n, h), 0.0), a2) * smithGgxCorrelatedV(nv, nl, a2) *
         schlickFresnel(f0, f90, std::max(glm::dot(v, h), 0.0));
}

}  // namespace engine
