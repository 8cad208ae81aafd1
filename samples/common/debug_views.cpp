#include "debug_views.h"

#include <algorithm>
#include <cmath>

namespace samples {
namespace {

struct Canvas {
  std::vector<uint8_t>& rgba;
  int width, height;
  void plot(int x, int y, glm::vec3 colour) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    uint8_t* p = &rgba[(size_t(y) * width + x) * 4];
    for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::clamp(colour[c], 0.0f, 1.0f) * 255.0f + 0.5f);
  }
  void line(glm::vec2 a, glm::vec2 b, glm::vec3 colour) {
    const int steps = int(std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y)))) + 1;
    for (int i = 0; i <= steps; ++i) {
      glm::vec2 p = a + (b - a) * (float(i) / float(steps));
      plot(int(std::floor(p.x)), int(std::floor(p.y)), colour);
    }
  }
  void circle(glm::vec2 c, float r, glm::vec3 colour) {
    const int steps = std::max(12, int(2.0f * 3.14159f * r));
    for (int i = 0; i < steps; ++i) {
      float t = 2.0f * 3.14159265f * float(i) / float(steps);
      plot(int(std::floor(c.x + r * std::cos(t))), int(std::floor(c.y + r * std::sin(t))), colour);
    }
  }
};

// Pixel position of a world point, or false behind the camera.
bool project(const glm::mat4& viewProj, glm::vec3 p, int width, int height, glm::vec2& pixel,
             float& w) {
  glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
  if (clip.w <= 0.0f) return false;
  w = clip.w;
  pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(width, height);
  return true;
}

}  // namespace

std::vector<uint8_t> drawVsglLobes(std::span<const uint8_t> rgba8, int width, int height,
                                   std::span<const gpu::Vsgl> vsgls, const glm::mat4& viewProj) {
  std::vector<uint8_t> out(rgba8.begin(), rgba8.end());
  for (size_t i = 0; i < out.size(); ++i)
    if (i % 4 != 3) out[i] = uint8_t(out[i] / 3);
  Canvas canvas{out, width, height};
  float largest = 0.0f;
  for (const gpu::Vsgl& v : vsgls)
    largest = std::max({largest, v.diffuse.power.a, v.specular.power.a});
  if (largest <= 0.0f) return out;
  const glm::vec2 focal(viewProj[0][0] * 0.5f * float(width),
                        viewProj[1][1] * 0.5f * float(height));
  for (const gpu::Vsgl& v : vsgls) {
    for (int lobe = 0; lobe < 2; ++lobe) {
      const gpu::VsglLobe& l = lobe == 0 ? v.diffuse : v.specular;
      if (l.power.a <= 0.0f) continue;
      glm::vec2 centre;
      float w = 0.0f;
      const glm::vec3 mean(l.meanVariance);
      if (!project(viewProj, mean, width, height, centre, w)) continue;
      // Three decades of power from dim to full colour.
      const float brightness =
          std::clamp(1.0f + std::log10(l.power.a / largest) / 3.0f, 0.15f, 1.0f);
      const glm::vec3 colour =
          brightness * (lobe == 0 ? glm::vec3(0.2f, 0.9f, 1.0f) : glm::vec3(1.0f, 0.6f, 0.1f));
      const float sigma = std::sqrt(std::max(l.meanVariance.w, 0.0f));
      const float radius = std::max(2.0f, 2.0f * sigma * std::abs(focal.y) / w);
      canvas.circle(centre, radius, colour);
      glm::vec2 tip;
      const float reach = std::max(2.0f * sigma, 0.05f * w);  // visible even for point-like lobes
      if (project(viewProj, mean + reach * glm::vec3(l.axisSharpness), width, height, tip, w))
        canvas.line(centre, tip, colour);
    }
  }
  return out;
}

std::vector<uint8_t> greyscale(std::span<const float> values) {
  std::vector<uint8_t> out(values.size() * 4, 255);
  for (size_t i = 0; i < values.size(); ++i) {
    const auto g = uint8_t(std::clamp(values[i], 0.0f, 1.0f) * 255.0f + 0.5f);
    out[4 * i] = out[4 * i + 1] = out[4 * i + 2] = g;
  }
  return out;
}

std::vector<uint8_t> levelColours(std::span<const uint8_t> rgba8, std::span<const float> levels) {
  static constexpr uint8_t kColours[4][3] = {
      {230, 40, 40}, {235, 200, 40}, {60, 190, 80}, {60, 110, 230}};
  std::vector<uint8_t> out(rgba8.begin(), rgba8.end());
  for (size_t i = 0; i < levels.size(); ++i) {
    if (levels[i] < 0.0f) continue;  // sky
    const uint8_t* c = kColours[std::min(size_t(levels[i]), size_t{3})];
    // Half the tint, half the frame's brightness: the level over the picture's structure.
    const int grey = (rgba8[4 * i] + rgba8[4 * i + 1] + rgba8[4 * i + 2]) / 3;
    for (int k = 0; k < 3; ++k) out[4 * i + k] = uint8_t((c[k] + grey) / 2);
  }
  return out;
}

uint32_t brightestVsgl(std::span<const gpu::Vsgl> vsgls) {
  uint32_t best = 0;
  float bestPower = -1.0f;
  for (uint32_t i = 0; i < vsgls.size(); ++i) {
    const float power = vsgls[i].diffuse.power.a + vsgls[i].specular.power.a;
    if (power > bestPower) bestPower = power, best = i;
  }
  return best;
}

}  // namespace samples
