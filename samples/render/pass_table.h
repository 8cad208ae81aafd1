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
  // One frame's time of a pass and the compute dispatches it recorded.
  void add(const std::string& name, double ms, uint32_t dispatches);
  // With the VSGL count and pixel count, the shading pass is also given per pixel-VSGL pair.
  void print(uint32_t frames, uint32_t vsglCount, uint32_t shadedPixels) const;

 private:
  std::vector<std::string> order_;
  std::map<std::string, std::vector<double>> times_;
  std::map<std::string, uint32_t> dispatches_;  // the last frame's
};

}  // namespace render
