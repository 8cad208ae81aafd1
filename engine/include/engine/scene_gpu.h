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
  // gpu::RasterCluster per RASTER_GROUP_SIZE triangles (engine/raster_clusters.h): the boxes the
  // rasterizer culls with. uploadScene fills it; for a host's buffers, ClusterBounds does.
  Buffer clusters;
  Image baseColorTextures;  // R8G8B8A8_SRGB array, one layer per base-colour texture
  Image dataTextures;       // R8G8B8A8_UNORM array, one layer per metallic-roughness texture
  Sampler sampler;          // trilinear, repeat
  uint32_t triangleCount = 0;
  // The buffers' element counts: the passes leave out a triangle that names a vertex past
  // vertexCount, and give one that names a material past materialCount no reflectance, so a
  // host's bad indices are never read out of bounds (gi::SceneGeometry).
  uint32_t vertexCount = 0;
  uint32_t materialCount = 0;
  uint32_t textureSize = 1;  // every layer is resampled to this square power-of-two size
  // Whether any material is alpha-tested (Material::alphaCutoff > 0): the rasterizer and the ISM
  // points then run their variants with the cut-out test (engine/alpha_cutout.h).
  bool alphaCutouts = false;
};

SceneGpu uploadScene(Context& ctx, const Scene& scene);

// The square side of every packed texture layer: the largest side of the materials' textures
// rounded up to a power of two, at most kMaxTextureSize.
int packedTextureSize(const Scene& scene);
// One texture as float RGBA in linear space (sRGB decoded for colour roles), resampled to
// size x size as its packed layer's top mip is.
std::vector<float> resampleLinear(const Texture& texture, bool srgb, int size);
// The alpha bytes of a texture's packed top mip (alpha is never sRGB-encoded), as the GPU's
// texelFetch of level 0 reads them.
std::vector<uint8_t> packedAlpha(const Texture& texture, int size);

}  // namespace engine
