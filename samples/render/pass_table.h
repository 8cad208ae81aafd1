// The sample renderer's table of per-pass GPU times over the measured frames (medians) and the
// compute dispatches each pass recorded.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace render {

// Per-pass GPU times over the measured frames, printed as medians.
class PassTable {
 public:
  // Starts a measured frame: a pass not added in it counts 0 ms and 0 dispatches there (a pass
  // the module kept from an earlier frame did not run).
  void beginFrame() { ++frames_; }
  // One frame's time of a pass and the compute dispatches it recorded.
  void add(const std::string& name, double ms, uint32_t dispatches);
  // With the VSGL count and pixel count, the shading pass is also given per pixel-VSGL pair.
  void print(uint32_t vsglCount, uint32_t shadedPixels) const;

 private:
  // A pass's times and dispatches in the measured frames it ran in, each frame's index first.
  struct Run {
    uint32_t frame;
    double ms;
    uint32_t dispatches;
  };
  std::vector<std::string> order_;
  std::map<std::string, std::vector<Run>> runs_;
  uint32_t frames_ = 0;
};

}  // namespace render
