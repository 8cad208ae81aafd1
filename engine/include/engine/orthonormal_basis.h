// An orthonormal basis around a unit vector (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited"): continuous except across n.z = 0, no normalisation. The same construction as the
// ISM frame of shaders/common/ism_lookup.glsl, in double.
#pragma once

#include <glm/glm.hpp>

namespace engine {

struct OrthonormalBasis {
  glm::dvec3 tangent;
  glm::dvec3 bitangent;
};

inline OrthonormalBasis orthonormalBasis(glm::dvec3 n) {
  const double s = n.z >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (s + n.z);
  const double b = n.x * n.y * a;
  return {{1.0 + s * n.x * n.x * a, s * b, -s * n.x}, {b, s + n.y * n.y * a, -n.y}};
}

}  // namespace engine
