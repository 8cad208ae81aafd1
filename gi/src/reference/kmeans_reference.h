// CPU twin of the k-means clustering baseline (vsgl-math.md section 9), in double: the oracle
// the GPU passes (gi/src/passes/kmeans.h) are tested against, step by step.
//
// The baseline clusters the RSM's texels (VPLs) instead of sampling kernels from its PDF: each
// iteration assigns every powered texel to its nearest centre, sums the same per-texel VSGL
// quantities as the filtered-importance path over each cluster, and moves each centre to its
// cluster's weighted mean (Lloyd's algorithm). The cluster sums become VSGLs through
// buildVsglLobe, the construction the filtered path uses.
//
// This work is based on:
//   [S3]    Tokuyoshi, "Modified Filtered Importance Sampling for Virtual Spherical Gaussian
//           Lights", Pacific Graphics 2016 short papers: k-means in 2-D image space and 3-D
//           world space as the baseline of its Tables 1-3 (assign, sort, sum).
//   [PKD12] Prutkin, Kaplanyan and Dachsbacher, "Reflective Shadow Map Clustering for
//           Real-Time Global Illumination", Eurographics 2012 short papers: clustering weighted
//           by view-dependent importance, started from the previous frame's centres.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "reference/vsgl_sampling.h"
#include "shared/kmeans.h"
#include "shared/vsgl.h"
#include "shared/vsgl_attributes.h"

namespace gi {

// Level 0 of the six attribute pyramids (shaders/shared/vsgl_attributes.h), size x size each.
using AttributeTexels = std::array<std::vector<glm::dvec4>, VSGL_ATTR_COUNT>;

// One RSM texel as the clustering sees it.
struct KmeansTexel {
  // KMEANS_SPACE_IMAGE: the texel centre in [0, 1]^2 (z = 0); KMEANS_SPACE_WORLD: the VPL's
  // position relative to the RSM origin, m (the power-weighted mean of its two lobes).
  glm::dvec3 feature{0.0};
  // Its weight in the centres and the cost: the PDF (KMEANS_WEIGHT_PDF) or 1
  // (KMEANS_WEIGHT_UNIFORM).
  double weight = 0.0;
  // Whether it carries power (w_d + w_s > 0). Every powered texel belongs to a cluster, so the
  // clusters hold all of the RSM's power; unpowered texels belong to none.
  bool powered = false;
};

std::vector<KmeansTexel> kmeansTexels(const AttributeTexels& texels, uint32_t size, uint32_t space,
                                      uint32_t weighting);

// Fresh centres, PDF-proportional and stratified: lattice point i of the Fibonacci lattice
// warped down the PDF pyramid (the filtered path's warp), centre i = the feature of the texel
// it lands in. An all-zero PDF gives centres at the origin.
std::vector<glm::dvec3> kmeansSeeds(const std::vector<KmeansTexel>& texels,
                                    const ScalarPyramid& pdf, uint32_t clusters);

// The assignment step: every powered texel to its nearest centre (squared Euclidean distance,
// ties to the lower index); unpowered texels get K, the cluster count (no cluster).
struct KmeansAssignment {
  std::vector<uint32_t> cluster;  // per texel
  std::vector<uint32_t> counts;   // members per cluster
  double cost = 0.0;              // sum of weight x squared distance to the nearest centre
};

KmeansAssignment assignReference(const std::vector<KmeansTexel>& texels,
                                 const std::vector<glm::dvec3>& centres);

// The empty-cluster rule, applied after the assignment: an empty cluster takes the texel that
// costs most (largest weight x squared distance; ties: lower texel index) in a donor cluster
// with at least two members. Donors are taken in order of that cost, highest first (ties: lower
// cluster index), one texel each; the empty clusters in index order. It lowers the cost after
// the centre update (the texel becomes a cluster of cost 0, its donor's cost falls), so the
// cost still never increases. Returns how many empty clusters were filled; clusters stay empty
// only when there are fewer donors than empty clusters (fewer powered texels than clusters).
uint32_t fillEmptyClustersReference(KmeansAssignment& assignment,
                                    const std::vector<KmeansTexel>& texels,
                                    const std::vector<glm::dvec3>& centres);

// The update step: per cluster, the sums of the six attributes over its members, the VSGL they
// make (buildVsglLobe; kernel = (0, 0, -1, members): a cluster has no mip level), and the new
// centre, the members' weighted mean feature (unchanged when their weights sum to 0).
struct KmeansClusters {
  std::vector<gpu::Vsgl> vsgls;
  std::vector<glm::dvec3> centres;
  std::vector<glm::dvec4> diffusePower;  // the diffuse power sums (tests check conservation)
  std::vector<glm::dvec4> specularPower;
};

KmeansClusters sumClustersReference(const AttributeTexels& texels,
                                    const std::vector<KmeansTexel>& clustered,
                                    const KmeansAssignment& assignment,
                                    const std::vector<glm::dvec3>& centres, glm::dvec3 origin);

struct KmeansReferenceSettings {
  uint32_t clusters = 128;
  uint32_t iterations = 4;
  uint32_t space = KMEANS_SPACE_IMAGE;
  uint32_t weighting = KMEANS_WEIGHT_PDF;
};

struct KmeansResult {
  std::vector<gpu::Vsgl> vsgls;
  std::vector<glm::dvec3> centres;    // after the last update (the next frame's start)
  std::vector<double> costs;          // per iteration, at its assignment
  std::vector<uint32_t> emptyFilled;  // per iteration, clusters the empty rule filled
};

// `iterations` rounds of assign, fill empty clusters, update, from `initial` centres or, when
// none are given, from kmeansSeeds. The PDF is the alpha of VSGL_ATTR_DIFFUSE_AXIS.
KmeansResult kmeansReference(const AttributeTexels& texels, uint32_t size, glm::dvec3 origin,
                             const KmeansReferenceSettings& settings,
                             const std::optional<std::vector<glm::dvec3>>& initial = {});

}  // namespace gi
