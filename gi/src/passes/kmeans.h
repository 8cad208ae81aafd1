// The k-means clustering baseline on the GPU (shaders/shared/kmeans.h, vsgl-math.md section 9):
// clusters the RSM's powered texels in 2-D image space or 3-D world space and turns each
// cluster into a VSGL with the filtered path's construction, so the two methods differ only in
// how texels are grouped. Per iteration: assign, fill empty clusters, radix sort, bounds, sum
// (5 dispatches + 3 per sort digit). CPU twin: gi/src/reference/kmeans_reference.h.
#pragma once

#include <string>

#include "engine/radix_sort.h"
#include "passes/vsgl_attributes.h"
#include "shared/kmeans.h"

namespace gi {

struct KmeansPassSettings {
  uint32_t clusters = 1024;                // K, [1, maxClusters]
  uint32_t iterations = 4;                 // Lloyd iterations per frame, >= 1
  uint32_t space = KMEANS_SPACE_IMAGE;     // KMEANS_SPACE_*
  uint32_t weighting = KMEANS_WEIGHT_PDF;  // KMEANS_WEIGHT_*
  // Start from the previous record's centres when it clustered the same K in the same space
  // (temporally coherent, [PKD12]); otherwise, and when false, from fresh PDF-proportional seeds.
  bool reuseCentres = true;
  // The record index of the first cluster's VSGL: the views of a point light write their
  // clusters one after another into the same buffer. first + clusters <= maxClusters.
  uint32_t first = 0;
};

class KmeansClustering {
 public:
  // `size`: the attribute pyramids' base size; `maxClusters` sizes the VSGL buffer.
  KmeansClustering(engine::Context& ctx, uint32_t size, uint32_t maxClusters,
                   std::string passPrefix = {});

  // Clusters the texels of `attributes` (level 0; the PDF is the diffuse axis map's alpha) and
  // writes K gpu::Vsgl records. Assumes every recorded command buffer is submitted: the next
  // record starts from the centres this one leaves.
  void record(VkCommandBuffer cmd, VsglAttributes& attributes, const RsmView& view,
              const KmeansPassSettings& settings, engine::GpuProfiler* profiler = nullptr);

  const engine::Buffer& vsgls() const { return vsgls_; }  // gpu::Vsgl[maxClusters]
  // vec4 per cluster (xyz = feature); tests upload their own and record with reuseCentres.
  engine::Buffer& centres() { return centres_; }
  // The last iteration's (cluster, texel) pairs sorted by cluster (uint32 each, size^2).
  const engine::Buffer& sortedClusters() const { return keys_; }
  const engine::Buffer& sortedTexels() const { return values_; }
  // Per iteration of the last record, the clusters the empty rule filled (uint32).
  const engine::Buffer& filledPerIteration() const { return stats_; }
  // Marks the centres buffer as holding K centres of `space` (after a test's upload).
  void adoptCentres(uint32_t clusters, uint32_t space);

  static constexpr uint32_t kMaxIterations = 64;

 private:
  uint32_t size_;
  uint32_t maxClusters_;
  std::string passPrefix_;
  engine::ComputeProgram seed_, assign_, fill_, bounds_, sum_;
  engine::RadixSort sort_;
  engine::Sampler sampler_;  // unused by texelFetch, but a combined image sampler needs one
  engine::Buffer centres_, keys_, values_, counts_, costliest_, ranges_, stats_, vsgls_;
  uint32_t centresClusters_ = 0;  // K and space the centres buffer holds (0: none)
  uint32_t centresSpace_ = 0;
};

}  // namespace gi
