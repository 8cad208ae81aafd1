// Scene buffers shared by every pass that reads geometry or materials (std430).
#ifndef SHADERS_SHARED_SCENE_DATA_H
#define SHADERS_SHARED_SCENE_DATA_H
#include "interop.h"

SHARED_BEGIN

// One world-space vertex: position with u in w, unit normal with v in w.
struct SceneVertex {
  vec4 positionU;
  vec4 normalV;
};

// glTF metallic-roughness material; texture layers index the packed 2-D array images
// (base colour: an sRGB array; metallic-roughness: a linear array). -1 = no texture.
struct SceneMaterial {
  vec4 baseColorFactor;  // linear RGBA
  // KHR_materials_specular: rgb = specularColorFactor, a = specularFactor (engine::Material).
  vec4 specular;
  float metallic;   // [0, 1]
  float roughness;  // perceptual roughness [0, 1]
  int baseColorLayer;
  int metallicRoughnessLayer;
  // KHR_texture_transform of each texture, the rows of a 2 x 3 affine map of (u, v, 1):
  // u' = dot(xyz, (u, v, 1)) with the U row, v' with the V row (engine::TextureTransform); w
  // unused.
  vec4 baseColorUvU;
  vec4 baseColorUvV;
  vec4 metallicRoughnessUvU;
  vec4 metallicRoughnessUvV;
  // glTF doubleSided: 1 = both faces reflect light; 0 = the back face reflects none in a light's
  // view (GBufferResolvePush::lightView), though it still blocks the light.
  uint doubleSided;
  // Tangent-space normal map (engine::Material::normalTexture): its layer in the linear
  // (metallic-roughness) array, -1 = none; the scale of its x and y; its transform's rows.
  int normalLayer;
  float normalScale;
  // Emission (engine::Material::emissiveFactor, emissiveTexture): its layer in the sRGB
  // (base colour) array, -1 = none; rgb the factor, a unused; its transform's rows.
  int emissiveLayer;
  vec4 normalUvU;
  vec4 normalUvV;
  vec4 emissive;
  vec4 emissiveUvU;
  vec4 emissiveUvV;
  // glTF alphaMode MASK (engine::Material::alphaCutoff): no surface where baseColorFactor.a x
  // the base colour layer's alpha lies below it (common/alpha_cutout.glsl); 0 = opaque.
  float alphaCutoff;
  uint pad0;
  uint pad1;
  uint pad2;
};

SHARED_END

SHARED_ASSERT_SIZE(SceneVertex, 32);
SHARED_ASSERT_SIZE(SceneMaterial, 224);
SHARED_ASSERT_OFFSET(SceneMaterial, metallic, 32);
#endif
