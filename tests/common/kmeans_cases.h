// The four k-means configurations the CPU and GPU tests run (feature space x weighting), and
// the RGB power sums they check conservation with.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "shared/kmeans.h"
#include "shared/vsgl.h"

namespace testing_common {

struct KmeansCase {
  uint32_t space;
  uint32_t weighting;
};

inline constexpr KmeansCase kKmeansCases[] = {{KMEANS_SPACE_IMAGE, KMEANS_WEIGHT_PDF},
                                              {KMEANS_SPACE_IMAGE, KMEANS_WEIGHT_UNIFORM},
                                              {KMEANS_SPACE_WORLD, KMEANS_WEIGHT_PDF},
                                              {KMEANS_SPACE_WORLD, KMEANS_WEIGHT_UNIFORM}};

inline std::string name(const KmeansCase& c) {
  return std::string(c.space == KMEANS_SPACE_IMAGE ? "image" : "world") + " space, " +
         (c.weighting == KMEANS_WEIGHT_PDF ? "PDF" : "uniform") + " weights";
}

// Summed (diffuse, specular) RGB power of a set of VSGLs, in double.
inline std::pair<glm::dvec3, glm::dvec3> powerSums(const std::vector<gpu::Vsgl>& vsgls) {
  glm::dvec3 diffuse(0.0), specular(0.0);
  for (const gpu::Vsgl& v : vsgls) {
    diffuse += glm::dvec3(v.diffuse.power);
    specular += glm::dvec3(v.specular.power);
  }
  return {diffuse, specular};
}

}  // namespace testing_common
