#include "engine/scene_gpu.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "engine/raster_clusters.h"
#include "engine/tonemap.h"
#include "shared/scene_data.h"

namespace engine {
namespace {

// One level's float RGBA (linear) as the bytes of its 8-bit format.
void encodeLevel(const std::vector<float>& level, bool srgb, std::vector<uint8_t>& out) {
  for (size_t i = 0; i < level.size(); ++i) {
    float c = std::clamp(level[i], 0.0f, 1.0f);
    if (srgb && i % 4 != 3) c = linearToSrgb(c);
    out.push_back(static_cast<uint8_t>(std::lround(c * 255.0f)));
  }
}

// Appends mip 0..n of one layer: 2x2 box means in linear space, then encoded to bytes.
void appendMipChain(std::vector<float> level, int size, bool srgb, std::vector<uint8_t>& out) {
  for (;;) {
    encodeLevel(level, srgb, out);
    if (size == 1) break;
    int half = size / 2;
    std::vector<float> next(static_cast<size_t>(half) * half * 4);
    for (int y = 0; y < half; ++y)
      for (int x = 0; x < half; ++x)
        for (int c = 0; c < 4; ++c) {
          auto at = [&](int xx, int yy) {
            return level[(static_cast<size_t>(yy) * size + xx) * 4 + c];
          };
          next[(static_cast<size_t>(y) * half + x) * 4 + c] =
              0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) +
                       at(2 * x + 1, 2 * y + 1));
        }
    level = std::move(next);
    size = half;
  }
}

Image makeTextureArray(Context& ctx, const Scene& scene, const std::vector<int>& textures,
                       bool srgb, int size) {
  uint32_t mips = static_cast<uint32_t>(std::bit_width(static_cast<unsigned>(size)));
  std::vector<uint8_t> texels;
  if (textures.empty()) {
    // Vulkan needs a layer to bind; materials never sample it (their layer index is -1).
    appendMipChain(std::vector<float>(static_cast<size_t>(size) * size * 4, 1.0f), size, false,
                   texels);
  }
  for (int index : textures)
    appendMipChain(resampleLinear(scene.textures[index], srgb, size), size, srgb, texels);
  ImageDesc desc;
  desc.width = desc.height = static_cast<uint32_t>(size);
  desc.layers = static_cast<uint32_t>(std::max<size_t>(1, textures.size()));
  desc.mips = mips;
  desc.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
  desc.arrayView = true;
  Image image(ctx, desc);
  image.upload(ctx, texels.data(), texels.size());
  return image;
}

template <class T>
Buffer makeStorage(Context& ctx, const std::vector<T>& data) {
  Buffer buffer(ctx, std::max<VkDeviceSize>(sizeof(T), data.size() * sizeof(T)),
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly);
  buffer.upload(ctx, data.data(), data.size() * sizeof(T));
  return buffer;
}

}  // namespace

// One texture as float RGBA in linear space, resampled to size x size (OpenImageIO's resize
// picks a filter suited to the scale factor).
std::vector<float> resampleLinear(const Texture& t, bool srgb, int size) {
  OIIO::ImageSpec spec(t.width, t.height, 4, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf src(spec);
  std::vector<float> linear(t.rgba8.size());
  for (size_t i = 0; i < linear.size(); ++i) {
    float c = static_cast<float>(t.rgba8[i]) / 255.0f;
    linear[i] = (srgb && i % 4 != 3) ? srgbToLinear(c) : c;
  }
  src.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, linear.data());
  if (t.width == size && t.height == size) return linear;
  OIIO::ImageBuf dst =
      OIIO::ImageBufAlgo::resize(src, "", 0.0f, OIIO::ROI(0, size, 0, size, 0, 1, 0, 4));
  if (dst.has_error()) throw Error(t.name + ": cannot resample texture: " + dst.geterror());
  std::vector<float> out(static_cast<size_t>(size) * size * 4);
  dst.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, out.data());
  return out;
}

std::vector<uint8_t> packedAlpha(const Texture& texture, int size) {
  std::vector<uint8_t> rgba;
  encodeLevel(resampleLinear(texture, false, size), false, rgba);
  std::vector<uint8_t> alpha(rgba.size() / 4);
  for (size_t i = 0; i < alpha.size(); ++i) alpha[i] = rgba[4 * i + 3];
  return alpha;
}

int packedTextureSize(const Scene& scene) {
  int largest = 1;
  for (const Material& m : scene.materials)
    for (int t :
         {m.baseColorTexture, m.metallicRoughnessTexture, m.normalTexture, m.emissiveTexture})
      if (t >= 0) largest = std::max({largest, scene.textures[t].width, scene.textures[t].height});
  return std::min(kMaxTextureSize, static_cast<int>(std::bit_ceil(static_cast<unsigned>(largest))));
}

SceneGpu uploadScene(Context& ctx, const Scene& scene) {
  SceneGpu gpu;
  gpu.triangleCount = scene.triangleCount();
  gpu.vertexCount = static_cast<uint32_t>(scene.positions.size());
  gpu.materialCount = static_cast<uint32_t>(scene.materials.size());

  std::vector<gpu::SceneVertex> vertices(scene.positions.size());
  for (size_t i = 0; i < vertices.size(); ++i) {
    glm::vec2 uv = i < scene.uvs.size() ? scene.uvs[i] : glm::vec2(0.0f);
    vertices[i].positionU = glm::vec4(scene.positions[i], uv.x);
    vertices[i].normalV = glm::vec4(scene.normals[i], uv.y);
  }

  // Each texture gets a layer in the array of the role that uses it (sRGB colour: base colour and
  // emission; linear data: metallic-roughness and normal maps); a texture used in both roles is
  // stored in both.
  std::vector<int> baseLayers, dataLayers;
  auto layerOf = [](std::vector<int>& layers, int texture) {
    if (texture < 0) return -1;
    auto it = std::find(layers.begin(), layers.end(), texture);
    if (it != layers.end()) return static_cast<int>(it - layers.begin());
    layers.push_back(texture);
    return static_cast<int>(layers.size() - 1);
  };
  std::vector<gpu::SceneMaterial> materials;
  for (const Material& m : scene.materials) {
    gpu::SceneMaterial g{};
    g.baseColorFactor = m.baseColorFactor;
    g.specular = glm::vec4(m.specularColorFactor, m.specularFactor);
    g.metallic = m.metallicFactor;
    g.roughness = m.roughnessFactor;
    g.baseColorLayer = layerOf(baseLayers, m.baseColorTexture);
    g.metallicRoughnessLayer = layerOf(dataLayers, m.metallicRoughnessTexture);
    g.doubleSided = m.doubleSided ? 1u : 0u;
    g.baseColorUvU = glm::vec4(glm::vec3(m.baseColorTransform.rowU()), 0.0f);
    g.baseColorUvV = glm::vec4(glm::vec3(m.baseColorTransform.rowV()), 0.0f);
    g.metallicRoughnessUvU = glm::vec4(glm::vec3(m.metallicRoughnessTransform.rowU()), 0.0f);
    g.metallicRoughnessUvV = glm::vec4(glm::vec3(m.metallicRoughnessTransform.rowV()), 0.0f);
    g.normalLayer = layerOf(dataLayers, m.normalTexture);
    g.normalScale = m.normalScale;
    g.normalUvU = glm::vec4(glm::vec3(m.normalTransform.rowU()), 0.0f);
    g.normalUvV = glm::vec4(glm::vec3(m.normalTransform.rowV()), 0.0f);
    g.emissiveLayer = layerOf(baseLayers, m.emissiveTexture);
    g.emissive = glm::vec4(m.emissiveFactor, 0.0f);
    g.emissiveUvU = glm::vec4(glm::vec3(m.emissiveTransform.rowU()), 0.0f);
    g.emissiveUvV = glm::vec4(glm::vec3(m.emissiveTransform.rowV()), 0.0f);
    g.alphaCutoff = m.alphaCutoff;
    gpu.alphaCutouts = gpu.alphaCutouts || m.alphaCutoff > 0.0f;
    materials.push_back(g);
  }
  const int size = packedTextureSize(scene);
  gpu.textureSize = static_cast<uint32_t>(size);

  gpu.vertices = makeStorage(ctx, vertices);
  gpu.indices = makeStorage(ctx, scene.indices);
  gpu.clusters = makeStorage(ctx, clusterBounds(scene));
  gpu.triangleMaterials = makeStorage(ctx, scene.triangleMaterial);
  gpu.materials = makeStorage(ctx, materials);
  gpu.baseColorTextures = makeTextureArray(ctx, scene, baseLayers, true, size);
  gpu.dataTextures = makeTextureArray(ctx, scene, dataLayers, false, size);
  gpu.sampler = Sampler(ctx);
  return gpu;
}

}  // namespace engine
