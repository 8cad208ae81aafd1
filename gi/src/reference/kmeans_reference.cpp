#include "reference/kmeans_reference.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace gi {
namespace {

double squaredDistance(glm::dvec3 a, glm::dvec3 b) {
  const glm::dvec3 d = a - b;
  return glm::dot(d, d);
}

}  // namespace

std::vector<KmeansTexel> kmeansTexels(const AttributeTexels& texels, uint32_t size, uint32_t space,
                                      uint32_t weighting) {
  std::vector<KmeansTexel> out(size_t{size} * size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const size_t i = size_t{y} * size + x;
      const double wd = texels[VSGL_ATTR_DIFFUSE_POWER][i].w;
      const double ws = texels[VSGL_ATTR_SPECULAR_POWER][i].w;
      KmeansTexel& t = out[i];
      t.powered = wd + ws > 0.0;
      if (!t.powered) continue;
      if (space == KMEANS_SPACE_IMAGE) {
        t.feature = glm::dvec3((x + 0.5) / size, (y + 0.5) / size, 0.0);
      } else {
        // Both position channels hold w y: their sum over w_d + w_s is y whichever lobe has power.
        t.feature = (glm::dvec3(texels[VSGL_ATTR_DIFFUSE_POSITION][i]) +
                     glm::dvec3(texels[VSGL_ATTR_SPECULAR_POSITION][i])) /
                    (wd + ws);
      }
      t.weight = weighting == KMEANS_WEIGHT_PDF ? texels[VSGL_ATTR_DIFFUSE_AXIS][i].w : 1.0;
    }
  return out;
}

std::vector<glm::dvec3> kmeansSeeds(const std::vector<KmeansTexel>& texels,
                                    const ScalarPyramid& pdf, uint32_t clusters) {
  std::vector<glm::dvec3> centres(clusters, glm::dvec3(0.0));
  if (!(pdf.levels.back()[0] > 0.0)) return centres;
  for (uint32_t i = 0; i < clusters; ++i) {
    const WarpResult warp = warpHierarchical(pdf, fibonacciPoint(i, clusters));
    centres[i] = texels[size_t{warp.texel.y} * pdf.size + warp.texel.x].feature;
  }
  return centres;
}

KmeansAssignment assignReference(const std::vector<KmeansTexel>& texels,
                                 const std::vector<glm::dvec3>& centres) {
  const auto clusters = static_cast<uint32_t>(centres.size());
  KmeansAssignment a;
  a.cluster.assign(texels.size(), clusters);
  a.counts.assign(clusters, 0u);
  for (size_t i = 0; i < texels.size(); ++i) {
    if (!texels[i].powered) continue;
    double best = std::numeric_limits<double>::infinity();
    uint32_t nearest = 0;
    for (uint32_t k = 0; k < clusters; ++k) {
      const double d = squaredDistance(texels[i].feature, centres[k]);
      if (d < best) {
        best = d;
        nearest = k;
      }
    }
    a.cluster[i] = nearest;
    ++a.counts[nearest];
    a.cost += texels[i].weight * best;
  }
  return a;
}

uint32_t fillEmptyClustersReference(KmeansAssignment& assignment,
                                    const std::vector<KmeansTexel>& texels,
                                    const std::vector<glm::dvec3>& centres) {
  const auto clusters = static_cast<uint32_t>(centres.size());
  std::vector<uint32_t> empty;
  for (uint32_t k = 0; k < clusters; ++k)
    if (assignment.counts[k] == 0) empty.push_back(k);
  if (empty.empty()) return 0;
  // Each cluster's costliest member: largest weight x squared distance, then lower index.
  constexpr size_t kNone = std::numeric_limits<size_t>::max();
  std::vector<size_t> costliest(clusters, kNone);
  std::vector<double> worst(clusters, -1.0);
  for (size_t i = 0; i < texels.size(); ++i) {
    const uint32_t k = assignment.cluster[i];
    if (k >= clusters) continue;
    const double c = texels[i].weight * squaredDistance(texels[i].feature, centres[k]);
    if (c > worst[k]) {
      worst[k] = c;
      costliest[k] = i;
    }
  }
  std::vector<uint32_t> donors;
  for (uint32_t k = 0; k < clusters; ++k)
    if (assignment.counts[k] >= 2) donors.push_back(k);
  std::stable_sort(donors.begin(), donors.end(),
                   [&](uint32_t a, uint32_t b) { return worst[a] > worst[b]; });
  const size_t filled = std::min(empty.size(), donors.size());
  for (size_t j = 0; j < filled; ++j) {
    const size_t texel = costliest[donors[j]];
    --assignment.counts[donors[j]];
    assignment.cluster[texel] = empty[j];
    assignment.counts[empty[j]] = 1;
  }
  return static_cast<uint32_t>(filled);
}

KmeansClusters sumClustersReference(const AttributeTexels& texels,
                                    const std::vector<KmeansTexel>& clustered,
                                    const KmeansAssignment& assignment,
                                    const std::vector<glm::dvec3>& centres, glm::dvec3 origin) {
  const size_t clusters = centres.size();
  std::vector<std::array<glm::dvec4, VSGL_ATTR_COUNT>> sums(clusters);
  for (auto& s : sums) s.fill(glm::dvec4(0.0));
  std::vector<glm::dvec4> weighted(clusters, glm::dvec4(0.0));  // xyz = sum w f, w = sum w
  for (size_t i = 0; i < clustered.size(); ++i) {
    const uint32_t k = assignment.cluster[i];
    if (k >= clusters) continue;
    for (int a = 0; a < VSGL_ATTR_COUNT; ++a) sums[k][a] += texels[a][i];
    weighted[k] += glm::dvec4(clustered[i].weight * clustered[i].feature, clustered[i].weight);
  }
  KmeansClusters out;
  out.vsgls.resize(clusters);
  out.centres = centres;
  for (size_t k = 0; k < clusters; ++k) {
    const auto& s = sums[k];
    gpu::Vsgl& v = out.vsgls[k];
    v.diffuse = buildVsglLobe(
        {s[VSGL_ATTR_DIFFUSE_POWER], s[VSGL_ATTR_DIFFUSE_POSITION], s[VSGL_ATTR_DIFFUSE_AXIS]},
        origin);
    v.specular = buildVsglLobe(
        {s[VSGL_ATTR_SPECULAR_POWER], s[VSGL_ATTR_SPECULAR_POSITION], s[VSGL_ATTR_SPECULAR_AXIS]},
        origin);
    v.kernel = glm::vec4(0.0f, 0.0f, -1.0f, static_cast<float>(assignment.counts[k]));
    if (weighted[k].w > 0.0) out.centres[k] = glm::dvec3(weighted[k]) / weighted[k].w;
    out.diffusePower.push_back(s[VSGL_ATTR_DIFFUSE_POWER]);
    out.specularPower.push_back(s[VSGL_ATTR_SPECULAR_POWER]);
  }
  return out;
}

KmeansResult kmeansReference(const AttributeTexels& texels, uint32_t size, glm::dvec3 origin,
                             const KmeansReferenceSettings& settings,
                             const std::optional<std::vector<glm::dvec3>>& initial) {
  const std::vector<KmeansTexel> clustered =
      kmeansTexels(texels, size, settings.space, settings.weighting);
  std::vector<double> pdf(clustered.size());
  for (size_t i = 0; i < pdf.size(); ++i) pdf[i] = texels[VSGL_ATTR_DIFFUSE_AXIS][i].w;
  KmeansResult r;
  r.centres =
      initial ? *initial : kmeansSeeds(clustered, makeScalarPyramid(pdf, size), settings.clusters);
  for (uint32_t it = 0; it < settings.iterations; ++it) {
    KmeansAssignment a = assignReference(clustered, r.centres);
    r.costs.push_back(a.cost);
    r.emptyFilled.push_back(fillEmptyClustersReference(a, clustered, r.centres));
    KmeansClusters c = sumClustersReference(texels, clustered, a, r.centres, origin);
    r.centres = std::move(c.centres);
    r.vsgls = std::move(c.vsgls);
  }
  return r;
}

}  // namespace gi
