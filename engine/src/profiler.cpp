#include "engine/profiler.h"

#include <algorithm>

namespace engine {

GpuProfiler::GpuProfiler(Context& ctx, uint32_t maxScopes)
    : ctx_(ctx),
      maxScopes_(maxScopes),
      nsPerTick_(static_cast<double>(ctx.properties().limits.timestampPeriod)) {
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2 * maxScopes;
  VK_CHECK(vkCreateQueryPool(ctx.device(), &info, nullptr, &pool_));
}

GpuProfiler::~GpuProfiler() {
  vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void GpuProfiler::beginFrame(VkCommandBuffer cmd) {
  names_.clear();
  dispatchesAtBegin_.clear();
  dispatches_.clear();
  vkCmdResetQueryPool(cmd, pool_, 0, 2 * maxScopes_);
}

uint32_t GpuProfiler::begin(VkCommandBuffer cmd, const std::string& name) {
  if (names_.size() >= maxScopes_)
    throw Error("GpuProfiler: more than " + std::to_string(maxScopes_) + " scopes in a frame");
  auto scope = static_cast<uint32_t>(names_.size());
  names_.push_back(name);
  dispatchesAtBegin_.push_back(ctx_.dispatchCount());
  dispatches_.push_back(0);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * scope);
  return scope;
}

void GpuProfiler::end(VkCommandBuffer cmd, uint32_t scope) {
  dispatches_[scope] = static_cast<uint32_t>(ctx_.dispatchCount() - dispatchesAtBegin_[scope]);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * scope + 1);
}

std::vector<PassTime> GpuProfiler::results(bool wait) const {
  std::vector<PassTime> out;
  if (names_.empty()) return out;
  std::vector<uint64_t> ticks(2 * names_.size());
  const VkResult status =
      vkGetQueryPoolResults(ctx_.device(), pool_, 0, static_cast<uint32_t>(ticks.size()),
                            ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                            VK_QUERY_RESULT_64_BIT | (wait ? VK_QUERY_RESULT_WAIT_BIT : 0));
  if (status == VK_NOT_READY) return out;
  VK_CHECK(status);
  for (size_t i = 0; i < names_.size(); ++i) {
    double ms = static_cast<double>(ticks[2 * i + 1] - ticks[2 * i]) * nsPerTick_ * 1e-6;
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const PassTime& p) { return p.name == names_[i]; });
    if (it != out.end()) {
      it->ms += ms;
      it->dispatches += dispatches_[i];
    } else {
      out.push_back({names_[i], ms, dispatches_[i]});
    }
  }
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace engine
