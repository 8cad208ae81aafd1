// G-buffer written by gbuffer_resolve.comp (and, later, by a host renderer). Encodings:
//   depth    R32_SFLOAT       Vulkan NDC depth in [0, 1]; 1 = background (nothing hit)
//   normal   R16G16_SNORM     world-space shading normal, octahedral (common/octahedral.glsl),
//                             flipped to face the viewer
//   diffuse  R16G16B16A16_SFLOAT  rgb = diffuse albedo (base colour * (1 - metallic)),
//                                 a = perceptual roughness r (GGX alpha = r^2)
//   specular R16G16B16A16_SFLOAT  rgb = F0, a = F90 of Schlick's Fresnel (common/brdf.glsl);
//                                 KHR_materials_specular scales a dielectric's pair
//                                 (gi/include/gi/indirect_lighting.h states the formulas)
// World positions are rebuilt from depth with the inverse view-projection matrix.
#ifndef SHADERS_SHARED_GBUFFER_H
#define SHADERS_SHARED_GBUFFER_H
#include "interop.h"

#define GBUFFER_GROUP_X 8
#define GBUFFER_GROUP_Y 8

SHARED_BEGIN

struct GBufferResolvePush {
  mat4 invViewProj;
  uvec2 viewport;
  // engine::BackFaces: 0 = every triangle seen from behind shades as its front (camera views);
  // 1 = a single-sided material's back face reflects nothing (light views: the RSM).
  uint backFaces;
  uint materialCount;  // a triangle naming a material at or past it reflects nothing
};

SHARED_END

SHARED_ASSERT_SIZE(GBufferResolvePush, 80);
#endif
