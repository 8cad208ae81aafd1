#include "pass_table.h"

#include <cstdio>

#include "engine/profiler.h"

namespace render {

void PassTable::add(const std::string& name, double ms, uint32_t dispatches) {
  if (!times_.count(name)) order_.push_back(name);
  times_[name].push_back(ms);
  dispatches_[name] = dispatches;
}

void PassTable::print(uint32_t frames, uint32_t vsglCount, uint32_t shadedPixels) const {
  std::printf("GPU time per pass, median of %u frames (ms), and compute dispatches per frame:\n",
              frames);
  for (const auto& name : order_) {
    const double ms = engine::median(times_.at(name));
    std::printf("  %-34s %9.3f %5u", name.c_str(), ms, dispatches_.at(name));
    if ((name == "gi vsgl shading" || name == "gi vpl shading") && vsglCount > 0)
      std::printf("   (%.2f ns per shaded pixel-%s pair)",
                  ms * 1e6 / (double(vsglCount) * shadedPixels),
                  name == "gi vpl shading" ? "VPL" : "VSGL");
    std::printf("\n");
  }
}

}  // namespace render
