#include "passes/kmeans.h"

#include <algorithm>
#include <bit>

#include "engine/commands.h"
#include "shared/vsgl.h"
#include "spirv/kmeans_assign.h"
#include "spirv/kmeans_bounds.h"
#include "spirv/kmeans_fill.h"
#include "spirv/kmeans_seed.h"
#include "spirv/kmeans_sum.h"

namespace gi {
namespace {

// The six attribute pyramids as combined image samplers, then `buffers` storage buffers.
std::vector<VkDescriptorType> attributesAnd(int buffers) {
  std::vector<VkDescriptorType> types(VSGL_ATTR_COUNT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  types.insert(types.end(), buffers, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  return types;
}

std::vector<VkDescriptorType> buffersOnly(int buffers) {
  return std::vector<VkDescriptorType>(buffers, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

engine::Buffer storage(engine::Context& ctx, VkDeviceSize bytes) {
  return engine::Buffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        engine::MemoryUsage::GpuOnly);
}

}  // namespace

KmeansClustering::KmeansClustering(engine::Context& ctx, uint32_t size, uint32_t maxClusters,
                                   std::string passPrefix)
    : size_(size),
      maxClusters_(maxClusters),
      passPrefix_(std::move(passPrefix)),
      seed_(ctx, "kmeans_seed", kKmeansSeedSpv, attributesAnd(1), sizeof(gpu::KmeansPush)),
      assign_(ctx, "kmeans_assign", kKmeansAssignSpv, attributesAnd(5), sizeof(gpu::KmeansPush)),
      fill_(ctx, "kmeans_fill", kKmeansFillSpv, buffersOnly(4), sizeof(gpu::KmeansPush)),
      bounds_(ctx, "kmeans_bounds", kKmeansBoundsSpv, buffersOnly(2), sizeof(gpu::KmeansPush)),
      sum_(ctx, "kmeans_sum", kKmeansSumSpv, attributesAnd(4), sizeof(gpu::KmeansPush)),
      sort_(ctx, size * size),
      sampler_(ctx, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
      centres_(storage(ctx, VkDeviceSize{maxClusters} * sizeof(glm::vec4))),
      keys_(storage(ctx, VkDeviceSize{size} * size * sizeof(uint32_t))),
      values_(storage(ctx, VkDeviceSize{size} * size * sizeof(uint32_t))),
      counts_(storage(ctx, VkDeviceSize{maxClusters} * sizeof(uint32_t))),
      costliest_(storage(ctx, VkDeviceSize{maxClusters} * sizeof(uint64_t))),
      ranges_(storage(ctx, VkDeviceSize{maxClusters} * sizeof(glm::uvec2))),
      stats_(storage(ctx, kMaxIterations * sizeof(uint32_t))),
      vsgls_(storage(ctx, VkDeviceSize{maxClusters} * sizeof(gpu::Vsgl))) {
  if (!std::has_single_bit(size))
    throw engine::Error("k-means: attribute size " + std::to_string(size) +
                        " is not a power of two");
}

void KmeansClustering::adoptCentres(uint32_t clusters, uint32_t space) {
  centresClusters_ = clusters;
  centresSpace_ = space;
}

void KmeansClustering::record(VkCommandBuffer cmd, VsglAttributes& attributes, const RsmView& view,
                              const KmeansPassSettings& settings, engine::GpuProfiler* profiler) {
  const uint32_t k = settings.clusters;
  if (k < 1 || k > maxClusters_ - std::min(settings.first, maxClusters_))
    throw engine::Error("k-means: cluster count " + std::to_string(k) + " from record " +
                        std::to_string(settings.first) + " outside [1, " +
                        std::to_string(maxClusters_) + "]");
  if (settings.iterations < 1 || settings.iterations > kMaxIterations)
    throw engine::Error("k-means: iterations " + std::to_string(settings.iterations) +
                        " outside [1, " + std::to_string(kMaxIterations) + "]");
  if (settings.space > KMEANS_SPACE_WORLD || settings.weighting > KMEANS_WEIGHT_UNIFORM)
    throw engine::Error("k-means: unknown feature space or weighting");
  if (attributes.pyramid(0).desc().width != size_)
    throw engine::Error("k-means: attribute pyramids are not " + std::to_string(size_) + "^2");

  const uint32_t texels = size_ * size_;
  gpu::KmeansPush push{};
  push.origin = glm::vec4(view.origin, 0.0f);
  push.clusters = k;
  push.size = size_;
  push.topLevel = static_cast<uint32_t>(std::countr_zero(size_));
  push.space = settings.space;
  push.weighting = settings.weighting;
  push.texelCount = texels;

  using engine::Binding;
  const VkSampler s = sampler_.handle();
  auto pyramid = [&](int a) { return Binding::sampled(attributes.pyramid(a), s); };
  const bool reuse =
      settings.reuseCentres && centresClusters_ == k && centresSpace_ == settings.space;
  if (!reuse) {
    engine::ProfileScope scope(profiler, cmd, passPrefix_ + "k-means seed");
    seed_.dispatch(cmd,
                   {pyramid(0), pyramid(1), pyramid(2), pyramid(3), pyramid(4), pyramid(5),
                    Binding::storage(centres_)},
                   push, engine::groupCount(k, KMEANS_SEED_GROUP));
    engine::computeBarrier(cmd);
  }
  engine::fillBuffer(cmd, stats_, 0u);
  // Keys reach K for unpowered texels: the sort needs bit_width(K) bits.
  const auto keyBits = static_cast<uint32_t>(std::bit_width(k));
  for (uint32_t it = 0; it < settings.iterations; ++it) {
    push.iteration = it;
    {
      engine::ProfileScope scope(profiler, cmd, passPrefix_ + "k-means assign");
      engine::fillBuffer(cmd, counts_, 0u, 0, VkDeviceSize{k} * sizeof(uint32_t));
      engine::fillBuffer(cmd, costliest_, 0u, 0, VkDeviceSize{k} * sizeof(uint64_t));
      assign_.dispatch(
          cmd,
          {pyramid(0), pyramid(1), pyramid(2), pyramid(3), pyramid(4), pyramid(5),
           Binding::storage(centres_), Binding::storage(keys_), Binding::storage(values_),
           Binding::storage(counts_), Binding::storage(costliest_)},
          push, engine::groupCount(texels, KMEANS_ASSIGN_GROUP * KMEANS_ASSIGN_TEXELS));
      engine::computeBarrier(cmd);
      fill_.dispatch(cmd,
                     {Binding::storage(keys_), Binding::storage(counts_),
                      Binding::storage(costliest_), Binding::storage(stats_)},
                     push, 1);
      engine::computeBarrier(cmd);
    }
    sort_.record(cmd, keys_, values_, texels, keyBits, profiler,
                 (passPrefix_ + "k-means sort").c_str());
    {
      engine::ProfileScope scope(profiler, cmd, passPrefix_ + "k-means sum");
      engine::fillBuffer(cmd, ranges_, 0u, 0, VkDeviceSize{k} * sizeof(glm::uvec2));
      bounds_.dispatch(cmd, {Binding::storage(keys_), Binding::storage(ranges_)}, push,
                       engine::groupCount(texels, KMEANS_BOUNDS_GROUP));
      engine::computeBarrier(cmd);
      sum_.dispatch(
          cmd,
          {pyramid(0), pyramid(1), pyramid(2), pyramid(3), pyramid(4), pyramid(5),
           Binding::storage(centres_), Binding::storage(values_), Binding::storage(ranges_),
           Binding::storage(vsgls_, VkDeviceSize{settings.first} * sizeof(gpu::Vsgl),
                            VkDeviceSize{k} * sizeof(gpu::Vsgl))},
          push, k);
      engine::computeBarrier(cmd);
    }
  }
  adoptCentres(k, settings.space);
}

}  // namespace gi
