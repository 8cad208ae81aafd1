#include "reprojection.h"

#include <cmath>

namespace flicker {
namespace {

// The surface point of pixel (x, y) of a `width` x `height` view from its NDC depth, rebuilt
// relative to the eye as the shading does (in double).
glm::dvec3 pointAt(const engine::RelativeUnprojection& u, uint32_t width, uint32_t height,
                   uint32_t x, uint32_t y, double depth) {
  const glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / glm::dvec2(width, height) * 2.0 - 1.0;
  const glm::dvec4 h = glm::dmat4(u.invViewProjRelative) * glm::dvec4(ndc, depth, 1.0);
  return glm::dvec3(u.eye) + glm::dvec3(h) / h.w;
}

}  // namespace

Reprojection reproject(const engine::GBufferData& previous, const engine::View& previousView,
                       const engine::GBufferData& current, const engine::View& currentView) {
  const size_t n = current.samples.size();
  Reprojection r{std::vector<std::array<uint32_t, 4>>(n), std::vector<std::array<double, 4>>(n),
                 std::vector<uint8_t>(n, 0)};
  const bool still = previousView.viewProj == currentView.viewProj;
  const engine::RelativeUnprojection now = engine::relativeUnprojection(currentView);
  const engine::RelativeUnprojection before = engine::relativeUnprojection(previousView);
  for (uint32_t y = 0; y < current.height; ++y)
    for (uint32_t x = 0; x < current.width; ++x) {
      const size_t i = size_t{y} * current.width + x;
      if (current.samples[i].background()) continue;
      if (still) {
        r.taps[i] = {uint32_t(i), 0, 0, 0};
        r.weights[i] = {1.0, 0.0, 0.0, 0.0};
        r.valid[i] = 1;
        continue;
      }
      const glm::dvec3 p =
          pointAt(now, current.width, current.height, x, y, current.samples[i].depth);
      const glm::dvec4 clip = glm::dmat4(previousView.viewProj) * glm::dvec4(p, 1.0);
      if (!(clip.w > 0.0)) continue;
      const glm::dvec2 pixel =
          (glm::dvec2(clip) / clip.w + 1.0) * 0.5 * glm::dvec2(previous.width, previous.height) -
          0.5;
      const glm::dvec2 base = glm::floor(pixel), f = pixel - base;
      const double tolerance = 0.01 * glm::length(p - glm::dvec3(before.eye));
      double total = 0.0;
      for (int k = 0; k < 4; ++k) {
        const int tx = int(base.x) + (k & 1), ty = int(base.y) + (k >> 1);
        r.weights[i][k] = 0.0;
        if (tx < 0 || ty < 0 || tx >= int(previous.width) || ty >= int(previous.height)) continue;
        const engine::GBufferSample& s = previous.at(uint32_t(tx), uint32_t(ty));
        if (s.background()) continue;
        const glm::dvec3 q =
            pointAt(before, previous.width, previous.height, uint32_t(tx), uint32_t(ty), s.depth);
        if (glm::length(q - p) > tolerance) continue;
        r.taps[i][k] = uint32_t(ty) * previous.width + uint32_t(tx);
        r.weights[i][k] = ((k & 1) ? f.x : 1.0 - f.x) * ((k >> 1) ? f.y : 1.0 - f.y);
        total += r.weights[i][k];
      }
      if (!(total > 0.0)) continue;
      for (double& w : r.weights[i]) w /= total;
      r.valid[i] = 1;
    }
  return r;
}

std::vector<glm::dvec3> resample(const std::vector<glm::dvec3>& image, const Reprojection& r) {
  std::vector<glm::dvec3> out(r.valid.size(), glm::dvec3(0.0));
  for (size_t i = 0; i < out.size(); ++i) {
    if (!r.valid[i]) continue;
    for (int k = 0; k < 4; ++k)
      if (r.weights[i][k] > 0.0) out[i] += r.weights[i][k] * image[r.taps[i][k]];
  }
  return out;
}

}  // namespace flicker
