// glTF alpha MASK: where a material's alpha lies below its cutoff there is no surface, for the
// camera, the light (the RSM and the host's shadow maps), the ISMs and the path tracer alike.
// One rule decides it everywhere, a yes-or-no answer that the GPU and its CPU twins find alike:
// the surface exists at texture coordinates uv when
//     baseColorFactor.a x alpha8 >= alphaCutoff x 255   (fp32, both products rounded once),
// alpha8 the byte of the base colour layer's top mip (as uploadScene packs it) at the texel that
// contains uv's fractional part, without filtering (a filtered alpha would blur the decision
// between texels, and its rounding would differ between the GPU and the twins). uv is the
// material's base colour coordinates: KHR_texture_transform applied to each vertex before the
// interpolation (the transform is affine, so this equals transforming the interpolated value).
// The GLSL side is shaders/common/alpha_cutout.glsl.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "engine/scene.h"

namespace engine {

class AlphaCutouts {
 public:
  // Resamples the alpha of each alpha-tested material's base colour texture as uploadScene does.
  explicit AlphaCutouts(const Scene& scene);

  // Whether any material is alpha-tested (Material::alphaCutoff > 0).
  bool any() const { return any_; }
  bool tested(uint32_t material) const { return materials_[material].cutoff > 0.0f; }
  // A vertex's coordinates in the base colour texture (the transform's rows in fp32, as
  // alpha_cutout.glsl evaluates them).
  glm::vec2 coordinates(uint32_t material, glm::vec2 uv) const;
  // Whether the surface of `material` exists at base colour coordinates `uv` (true for a
  // material that is not alpha-tested, and for non-finite coordinates).
  bool opaque(uint32_t material, glm::vec2 uv) const;
  // The same at barycentrics (b1, b2) of a triangle whose corners carry `vertexUvs`: each
  // corner's coordinates, then c0 + b1 (c1 - c0) + b2 (c2 - c0) in fp32 (ism_points.comp's
  // order; the path tracer's hits use it too).
  bool opaqueAt(uint32_t material, const glm::vec2 vertexUvs[3], glm::vec2 barycentrics) const;

 private:
  struct Mask {
    float cutoff = 0.0f;
    float alphaFactor = 1.0f;
    glm::vec3 rowU{1.0f, 0.0f, 0.0f};
    glm::vec3 rowV{0.0f, 1.0f, 0.0f};
    int texture = -1;  // index into alpha_, -1: the factor alone
  };
  std::vector<Mask> materials_;
  std::vector<std::vector<uint8_t>> alpha_;  // size x size bytes per texture
  int size_ = 1;
  bool any_ = false;
};

}  // namespace engine
