#include "pass_table.h"

#include <cstdio>

#include "engine/profiler.h"

namespace render {

void PassTable::add(const std::string& name, double ms, uint32_t dispatches) {
  if (!runs_.count(name)) order_.push_back(name);
  runs_[name].push_back({frames_ - 1, ms, dispatches});
}

void PassTable::print(uint32_t vsglCount, uint32_t shadedPixels) const {
  std::printf(
      "GPU time per pass, median of %u frames (ms; 0 in a frame it did not run), and compute "
      "dispatches per frame (median):\n",
      frames_);
  for (const auto& name : order_) {
    std::vector<double> times(frames_, 0.0), dispatches(frames_, 0.0);
    for (const Run& run : runs_.at(name)) {
      times[run.frame] += run.ms;
      dispatches[run.frame] += run.dispatches;
    }
    const double ms = engine::median(times);
    std::printf("  %-34s %9.3f %5.0f", name.c_str(), ms, engine::median(dispatches));
    if ((name == "gi vsgl shading" || name == "gi vpl shading") && vsglCount > 0 && ms > 0.0)
      std::printf("   (%.2f ns per shaded pixel-%s pair)",
                  ms * 1e6 / (double(vsglCount) * shadedPixels),
                  name == "gi vpl shading" ? "VPL" : "VSGL");
    std::printf("\n");
  }
}

}  // namespace render
