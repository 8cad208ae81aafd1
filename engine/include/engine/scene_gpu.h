// A Scene uploaded for the compute passes: world-space vertices, indices, per-triangle material
// ids, materials, and the textures packed into two 2-D array images with full mip chains
// (lavapipe has no descriptor indexing, so one array replaces a bindless texture table).
#pragma once

#include "engine/buffer.h"
#include "engine/image.h"
#include "engine/scene.h"

namespace engine {

struct SceneGpu {
  Buffer vertices;           // gpu::SceneVertex per vertex
  Buffer indices;            // uint32 x 3 per triangle
  Buffer triangleMaterials;  // uint32 per triangle
  Buffer materials;          // gpu::SceneMaterial per material
  Image baseColorTextures;   // R8G8B8A8_SRGB array, one layer per base-colour texture
  Image dataTextures;        // R8G8B8A8_UNORM array, one layer per metallic-roughness texture
  Sampler sampler;           // trilinear, repeat
  uint32_t triangleCount = 0;
  uint32_t textureSize = 1;  // every layer is resampled to this square power-of-two size
};

SceneGpu uploadScene(Context& ctx, const Scene& scene);

}  // namespace engine
