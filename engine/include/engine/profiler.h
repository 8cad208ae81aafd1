// GPU timestamps around named passes. A pass's time runs from the end of all earlier work to
// the end of its own, so barriers and pipeline bubbles are charged to the pass that waits.
#pragma once

#include <string>
#include <vector>

#include "engine/vk_context.h"

namespace engine {

struct PassTime {
  std::string name;
  double ms = 0.0;
  uint32_t dispatches = 0;  // compute dispatches the pass recorded
};

class GpuProfiler {
 public:
  explicit GpuProfiler(Context& ctx, uint32_t maxScopes = 64);
  ~GpuProfiler();
  GpuProfiler(const GpuProfiler&) = delete;
  GpuProfiler& operator=(const GpuProfiler&) = delete;

  // Resets the queries; call once per recorded frame before any begin().
  void beginFrame(VkCommandBuffer cmd);
  uint32_t begin(VkCommandBuffer cmd, const std::string& name);
  void end(VkCommandBuffer cmd, uint32_t scope);

  // Per-pass times and dispatch counts of the last recorded frame; valid once its submission
  // has completed. Scopes with the same name are summed (e.g. one shadow pass per light). With wait
  // = false (a host's device, where we never wait) an unfinished frame gives an empty list.
  std::vector<PassTime> results(bool wait = true) const;

 private:
  Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t maxScopes_;
  std::vector<std::string> names_;
  std::vector<uint64_t> dispatchesAtBegin_;  // per scope; turned into counts by end()
  std::vector<uint32_t> dispatches_;
  double nsPerTick_;
};

// Median of per-frame pass times (the even-count median is the mean of the middle two); 0 if empty.
double median(std::vector<double> values);

// Times the enclosing block as one named pass; a null profiler makes it free.
class ProfileScope {
 public:
  ProfileScope(GpuProfiler* profiler, VkCommandBuffer cmd, const std::string& name)
      : profiler_(profiler), cmd_(cmd), scope_(profiler ? profiler->begin(cmd, name) : 0) {}
  ~ProfileScope() {
    if (profiler_) profiler_->end(cmd_, scope_);
  }
  ProfileScope(const ProfileScope&) = delete;
  ProfileScope& operator=(const ProfileScope&) = delete;

 private:
  GpuProfiler* profiler_;
  VkCommandBuffer cmd_;
  uint32_t scope_;
};

}  // namespace engine
