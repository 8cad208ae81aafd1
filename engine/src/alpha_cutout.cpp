#include "engine/alpha_cutout.h"

#include <algorithm>
#include <cmath>

#include "engine/scene_gpu.h"

namespace engine {

AlphaCutouts::AlphaCutouts(const Scene& scene) : size_(packedTextureSize(scene)) {
  std::vector<int> resampled;  // scene texture of each alpha_ entry
  for (const Material& m : scene.materials) {
    Mask mask;
    mask.cutoff = m.alphaCutoff;
    mask.alphaFactor = m.baseColorFactor.a;
    mask.rowU = glm::vec3(m.baseColorTransform.rowU());
    mask.rowV = glm::vec3(m.baseColorTransform.rowV());
    if (m.alphaCutoff > 0.0f && m.baseColorTexture >= 0) {
      auto it = std::find(resampled.begin(), resampled.end(), m.baseColorTexture);
      if (it == resampled.end()) {
        resampled.push_back(m.baseColorTexture);
        alpha_.push_back(packedAlpha(scene.textures[m.baseColorTexture], size_));
        it = resampled.end() - 1;
      }
      mask.texture = static_cast<int>(it - resampled.begin());
    }
    any_ = any_ || m.alphaCutoff > 0.0f;
    materials_.push_back(mask);
  }
}

glm::vec2 AlphaCutouts::coordinates(uint32_t material, glm::vec2 uv) const {
  const Mask& m = materials_[material];
  // ((r.x u + r.y v) + r.z), each product and sum rounded to fp32 (no contraction).
  const auto row = [&](const glm::vec3& r) {
    const float a = r.x * uv.x;
    const float b = r.y * uv.y;
    const float s = a + b;
    return s + r.z;
  };
  return {row(m.rowU), row(m.rowV)};
}

bool AlphaCutouts::opaque(uint32_t material, glm::vec2 uv) const {
  const Mask& m = materials_[material];
  if (!(m.cutoff > 0.0f)) return true;
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return true;
  float alpha8 = 255.0f;
  if (m.texture >= 0) {
    // The texel containing uv's fractional part (repeat addressing); the fraction can round to
    // 1 for a coordinate just below an integer.
    const auto texel = [&](float c) {
      const float f = c - std::floor(c);
      return std::min(static_cast<int>(f * static_cast<float>(size_)), size_ - 1);
    };
    const size_t index = static_cast<size_t>(texel(uv.y)) * size_ + texel(uv.x);
    alpha8 = static_cast<float>(alpha_[m.texture][index]);
  }
  const float alpha = alpha8 * m.alphaFactor;
  const float cutoff = m.cutoff * 255.0f;
  return alpha >= cutoff;
}

bool AlphaCutouts::opaqueAt(uint32_t material, const glm::vec2 vertexUvs[3],
                            glm::vec2 barycentrics) const {
  if (!tested(material)) return true;
  glm::vec2 c[3];
  for (int k = 0; k < 3; ++k) c[k] = coordinates(material, vertexUvs[k]);
  return opaque(material, c[0] + barycentrics.x * (c[1] - c[0]) + barycentrics.y * (c[2] - c[0]));
}

}  // namespace engine
