// engine::Scene -> one self-contained .gltf (plus one PNG per texture). The JSON is built with
// nlohmann::json directly rather than through tinygltf's serializer, which writes glTF-invalid
// values for our defaults (e.g. "zfar": 0 for an infinite perspective camera).
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "engine/error.h"
#include "engine/gltf.h"
#include "engine/image_io.h"

namespace engine {
namespace {

using nlohmann::json;

// glTF enums (glTF 2.0 spec, 5.1.x, 5.26.x).
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kLinear = 9729;
constexpr int kLinearMipmapLinear = 9987;
constexpr int kRepeat = 10497;

// The shortest decimal that reads back as the same float, so the JSON shows 0.1 rather than
// 0.10000000149011612 while loading still gives back the exact float.
double tidy(float value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  *result.ptr = '\0';
  return std::strtod(text, nullptr);
}

json tidyArray(std::span<const float> values) {
  json array = json::array();
  for (float v : values) array.push_back(tidy(v));
  return array;
}

// Whether a material differs from KHR_materials_specular's defaults (written only then).
bool hasSpecular(const Material& m) {
  return m.specularFactor != 1.0f || m.specularColorFactor != glm::vec3(1.0f);
}

// The largest channel of a material's emission: above 1, what KHR_materials_emissive_strength
// carries when it is written.
float emissiveStrength(const Material& m) {
  return std::max({m.emissiveFactor.r, m.emissiveFactor.g, m.emissiveFactor.b});
}

// Whether a material's textures carry a KHR_texture_transform (written only then).
bool hasTextureTransform(const Material& m) {
  return (m.baseColorTexture >= 0 && !m.baseColorTransform.identity()) ||
         (m.metallicRoughnessTexture >= 0 && !m.metallicRoughnessTransform.identity()) ||
         (m.normalTexture >= 0 && !m.normalTransform.identity()) ||
         (m.emissiveTexture >= 0 && !m.emissiveTransform.identity());
}

// A textureInfo: the texture's index, and its transform when it has one.
json textureInfo(int index, const TextureTransform& t) {
  json info = {{"index", index}};
  if (!t.identity())
    info["extensions"] = {{"KHR_texture_transform",
                           {{"offset", tidyArray({&t.offset.x, 2})},
                            {"rotation", tidy(t.rotation)},
                            {"scale", tidyArray({&t.scale.x, 2})}}}};
  return info;
}

std::string base64(std::span<const uint8_t> bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t chunk = uint32_t{bytes[i]} << 16;
    if (n > 1) chunk |= uint32_t{bytes[i + 1]} << 8;
    if (n > 2) chunk |= uint32_t{bytes[i + 2]};
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += n > 1 ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += n > 2 ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

// The single binary buffer, its views and accessors (one view per accessor, 4-byte aligned).
class BufferBuilder {
 public:
  template <typename T>
  int addAccessor(std::span<const T> elements, int componentType, const char* type, int target,
                  const std::optional<std::pair<json, json>>& minMax = std::nullopt) {
    while (data_.size() % 4 != 0) data_.push_back(0);
    const size_t offset = data_.size();
    const size_t byteLength = elements.size_bytes();
    data_.resize(offset + byteLength);
    if (byteLength > 0) std::memcpy(data_.data() + offset, elements.data(), byteLength);
    views_.push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", byteLength}, {"target", target}});
    json accessor = {{"bufferView", views_.size() - 1},
                     {"componentType", componentType},
                     {"count", elements.size()},
                     {"type", type}};
    if (minMax) {
      accessor["min"] = minMax->first;
      accessor["max"] = minMax->second;
    }
    accessors_.push_back(std::move(accessor));
    return static_cast<int>(accessors_.size() - 1);
  }

  void writeInto(json& gltf) const {
    if (accessors_.empty()) return;
    gltf["buffers"] =
        json::array({{{"byteLength", data_.size()},
                      {"uri", "data:application/octet-stream;base64," + base64(data_)}}});
    gltf["bufferViews"] = views_;
    gltf["accessors"] = accessors_;
  }

 private:
  std::vector<uint8_t> data_;
  json views_ = json::array();
  json accessors_ = json::array();
};

json matrixJson(const glm::mat4& m) {
  json values = json::array();
  for (int column = 0; column < 4; ++column) {
    for (int row = 0; row < 4; ++row) values.push_back(tidy(m[column][row]));
  }
  return values;  // column-major, as glTF expects
}

// A node frame whose -Z is `direction` (KHR_lights_punctual lights shine down -Z), stored as
// fileLightDirection keeps it so that the loader reads back the same floats.
glm::mat4 lightFrame(const Light& light) {
  const glm::vec3 z = -fileLightDirection(light.direction).value_or(glm::vec3(0.0f, 0.0f, -1.0f));
  const glm::vec3 up =
      std::abs(z.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 x = glm::normalize(glm::cross(up, z));
  const glm::vec3 y = glm::cross(z, x);
  return glm::mat4(glm::vec4(x, 0.0f), glm::vec4(y, 0.0f), glm::vec4(z, 0.0f),
                   glm::vec4(light.position, 1.0f));
}

class GltfBuilder {
 public:
  GltfBuilder(const Scene& scene, const std::string& path) : scene_(scene), path_(path) {}

  [[noreturn]] void fail(const std::string& problem) const { throw Error(path_ + ": " + problem); }

  void validate() const {
    const size_t vertexCount = scene_.positions.size();
    if (scene_.normals.size() != vertexCount || scene_.uvs.size() != vertexCount) {
      fail("scene has mismatched position/normal/uv counts");
    }
    if (scene_.indices.size() % 3 != 0 ||
        scene_.triangleMaterial.size() != scene_.triangleCount()) {
      fail("scene has mismatched index/triangle-material counts");
    }
    for (uint32_t index : scene_.indices) {
      if (index >= vertexCount) fail("scene index " + std::to_string(index) + " is out of range");
    }
    for (uint32_t material : scene_.triangleMaterial) {
      if (material >= scene_.materials.size()) {
        fail("scene material " + std::to_string(material) + " does not exist");
      }
    }
    for (const Material& material : scene_.materials) {
      for (int texture : {material.baseColorTexture, material.metallicRoughnessTexture,
                          material.normalTexture, material.emissiveTexture}) {
        if (texture < -1 || texture >= static_cast<int>(scene_.textures.size())) {
          fail("material '" + material.name + "' uses texture " + std::to_string(texture) +
               " which does not exist");
        }
      }
    }
    for (const Light& light : scene_.lights) {
      if (!(glm::length(light.direction) > 0.0f)) {
        fail("light '" + light.name + "' has no direction");
      }
    }
    for (const Camera& camera : scene_.cameras) {
      if (!camera.perspective && !(camera.zfar > camera.znear)) {
        fail("orthographic camera '" + camera.name + "' needs zfar > znear");
      }
    }
  }

  json build(const std::vector<std::string>& imageUris) {
    json gltf;
    gltf["asset"] = {{"version", "2.0"}, {"generator", "vsgl engine::writeGltf"}};
    json nodes = json::array();
    if (!scene_.indices.empty()) {
      gltf["meshes"] = json::array({{{"primitives", buildPrimitives()}}});
      nodes.push_back({{"mesh", 0}});
    }
    buffer_.writeInto(gltf);
    if (!scene_.materials.empty()) gltf["materials"] = buildMaterials();
    if (!imageUris.empty()) {
      // Written so other viewers match the loader's fixed assumption (see gltf.h).
      gltf["samplers"] = json::array({{{"magFilter", kLinear},
                                       {"minFilter", kLinearMipmapLinear},
                                       {"wrapS", kRepeat},
                                       {"wrapT", kRepeat}}});
      json images = json::array();
      json textures = json::array();
      for (size_t i = 0; i < imageUris.size(); ++i) {
        images.push_back({{"uri", imageUris[i]}});
        textures.push_back({{"sampler", 0}, {"source", i}});
      }
      gltf["images"] = std::move(images);
      gltf["textures"] = std::move(textures);
    }
    if (!scene_.cameras.empty()) {
      json cameras = json::array();
      for (size_t c = 0; c < scene_.cameras.size(); ++c) {
        const Camera& camera = scene_.cameras[c];
        cameras.push_back(cameraJson(camera));
        json node = {{"camera", c}, {"matrix", matrixJson(camera.cameraToWorld)}};
        if (!camera.name.empty()) node["name"] = camera.name;
        nodes.push_back(std::move(node));
      }
      gltf["cameras"] = std::move(cameras);
    }
    if (!scene_.lights.empty()) {
      json lights = json::array();
      for (size_t l = 0; l < scene_.lights.size(); ++l) {
        const Light& light = scene_.lights[l];
        lights.push_back(lightJson(light));
        json node = {{"extensions", {{"KHR_lights_punctual", {{"light", l}}}}},
                     {"matrix", matrixJson(lightFrame(light))}};
        if (!light.name.empty()) node["name"] = light.name;
        nodes.push_back(std::move(node));
      }
      gltf["extensions"] = {{"KHR_lights_punctual", {{"lights", std::move(lights)}}}};
      gltf["extensionsUsed"] = json::array({"KHR_lights_punctual"});
    }
    if (std::any_of(scene_.materials.begin(), scene_.materials.end(), hasSpecular))
      gltf["extensionsUsed"].push_back("KHR_materials_specular");
    if (std::any_of(scene_.materials.begin(), scene_.materials.end(),
                    [](const Material& m) { return emissiveStrength(m) > 1.0f; }))
      gltf["extensionsUsed"].push_back("KHR_materials_emissive_strength");
    if (std::any_of(scene_.materials.begin(), scene_.materials.end(), hasTextureTransform))
      gltf["extensionsUsed"].push_back("KHR_texture_transform");
    if (!nodes.empty()) {  // glTF arrays, when present, must not be empty
      json rootNodes = json::array();
      for (size_t i = 0; i < nodes.size(); ++i) rootNodes.push_back(i);
      gltf["nodes"] = std::move(nodes);
      gltf["scenes"] = json::array({{{"nodes", std::move(rootNodes)}}});
      gltf["scene"] = 0;
    }
    return gltf;
  }

 private:
  // One primitive per run of consecutive triangles with the same material, so the loader gives
  // back the triangles in the same order. Each primitive carries only the vertices it uses.
  json buildPrimitives() {
    json primitives = json::array();
    const uint32_t triangleCount = scene_.triangleCount();
    constexpr uint32_t kUnused = ~0u;
    std::vector<uint32_t> localIndex(scene_.positions.size(), kUnused);
    uint32_t runStart = 0;
    while (runStart < triangleCount) {
      const uint32_t material = scene_.triangleMaterial[runStart];
      uint32_t runEnd = runStart;
      while (runEnd < triangleCount && scene_.triangleMaterial[runEnd] == material) ++runEnd;

      std::vector<uint32_t> vertices;  // scene vertex of each primitive vertex
      std::vector<uint32_t> indices;
      for (uint32_t i = 3 * runStart; i < 3 * runEnd; ++i) {
        const uint32_t v = scene_.indices[i];
        if (localIndex[v] == kUnused) {
          localIndex[v] = static_cast<uint32_t>(vertices.size());
          vertices.push_back(v);
        }
        indices.push_back(localIndex[v]);
      }
      std::vector<glm::vec3> positions;
      std::vector<glm::vec3> normals;
      std::vector<glm::vec2> uvs;
      glm::vec3 lo(std::numeric_limits<float>::max());
      glm::vec3 hi(std::numeric_limits<float>::lowest());
      for (uint32_t v : vertices) {
        positions.push_back(scene_.positions[v]);
        normals.push_back(scene_.normals[v]);
        uvs.push_back(scene_.uvs[v]);
        lo = glm::min(lo, scene_.positions[v]);
        hi = glm::max(hi, scene_.positions[v]);
        localIndex[v] = kUnused;  // reset for the next run
      }
      // glTF requires min/max on POSITION accessors.
      const auto bounds = std::make_pair(tidyArray({&lo.x, 3}), tidyArray({&hi.x, 3}));
      json attributes = {{"POSITION", buffer_.addAccessor(std::span<const glm::vec3>(positions),
                                                          kFloat, "VEC3", kArrayBuffer, bounds)},
                         {"NORMAL", buffer_.addAccessor(std::span<const glm::vec3>(normals), kFloat,
                                                        "VEC3", kArrayBuffer)},
                         {"TEXCOORD_0", buffer_.addAccessor(std::span<const glm::vec2>(uvs), kFloat,
                                                            "VEC2", kArrayBuffer)}};
      const int indexAccessor = buffer_.addAccessor(std::span<const uint32_t>(indices),
                                                    kUnsignedInt, "SCALAR", kElementArrayBuffer);
      primitives.push_back({{"attributes", std::move(attributes)},
                            {"indices", indexAccessor},
                            {"material", material},
                            {"mode", 4}});
      runStart = runEnd;
    }
    return primitives;
  }

  json buildMaterials() const {
    json materials = json::array();
    for (const Material& material : scene_.materials) {
      json pbr = {{"baseColorFactor", tidyArray({&material.baseColorFactor.x, 4})},
                  {"metallicFactor", tidy(material.metallicFactor)},
                  {"roughnessFactor", tidy(material.roughnessFactor)}};
      if (material.baseColorTexture >= 0)
        pbr["baseColorTexture"] =
            textureInfo(material.baseColorTexture, material.baseColorTransform);
      if (material.metallicRoughnessTexture >= 0)
        pbr["metallicRoughnessTexture"] =
            textureInfo(material.metallicRoughnessTexture, material.metallicRoughnessTransform);
      json out = {{"pbrMetallicRoughness", std::move(pbr)}, {"doubleSided", material.doubleSided}};
      if (material.normalTexture >= 0) {
        out["normalTexture"] = textureInfo(material.normalTexture, material.normalTransform);
        out["normalTexture"]["scale"] = tidy(material.normalScale);
      }
      // glTF's emissiveFactor lies in [0, 1]: a brighter emission is written with its largest
      // channel as KHR_materials_emissive_strength.
      const float strength = emissiveStrength(material);
      if (strength > 0.0f) {
        const glm::vec3 factor = material.emissiveFactor / std::max(strength, 1.0f);
        out["emissiveFactor"] = tidyArray({&factor.x, 3});
        if (material.emissiveTexture >= 0)
          out["emissiveTexture"] =
              textureInfo(material.emissiveTexture, material.emissiveTransform);
      }
      if (material.alphaCutoff > 0.0f) {
        out["alphaMode"] = "MASK";
        out["alphaCutoff"] = tidy(material.alphaCutoff);
      }
      if (hasSpecular(material))
        out["extensions"]["KHR_materials_specular"] = {
            {"specularFactor", tidy(material.specularFactor)},
            {"specularColorFactor", tidyArray({&material.specularColorFactor.x, 3})}};
      if (strength > 1.0f)
        out["extensions"]["KHR_materials_emissive_strength"] = {
            {"emissiveStrength", tidy(strength)}};
      if (!material.name.empty()) out["name"] = material.name;
      materials.push_back(std::move(out));
    }
    return materials;
  }

  static json cameraJson(const Camera& camera) {
    json out;
    if (camera.perspective) {
      json perspective = {{"yfov", tidy(camera.yfov)}, {"znear", tidy(camera.znear)}};
      // Absent means "from the viewport" and "infinite" in glTF, as 0 does in engine::Camera.
      if (camera.aspectRatio > 0.0f) perspective["aspectRatio"] = tidy(camera.aspectRatio);
      if (camera.zfar > 0.0f) perspective["zfar"] = tidy(camera.zfar);
      out = {{"type", "perspective"}, {"perspective", std::move(perspective)}};
    } else {
      out = {{"type", "orthographic"},
             {"orthographic",
              {{"xmag", tidy(camera.xmag)},
               {"ymag", tidy(camera.ymag)},
               {"znear", tidy(camera.znear)},
               {"zfar", tidy(camera.zfar)}}}};
    }
    if (!camera.name.empty()) out["name"] = camera.name;
    return out;
  }

  static json lightJson(const Light& light) {
    static constexpr const char* kTypeNames[] = {"directional", "point", "spot"};
    json out = {{"type", kTypeNames[static_cast<uint32_t>(light.type)]},
                {"color", tidyArray({&light.color.x, 3})},
                {"intensity", tidy(light.intensity)}};
    if (light.range > 0.0f) out["range"] = tidy(light.range);
    if (light.type == LightType::Spot) {
      out["spot"] = {{"innerConeAngle", tidy(light.innerConeAngle)},
                     {"outerConeAngle", tidy(light.outerConeAngle)}};
    }
    if (!light.name.empty()) out["name"] = light.name;
    return out;
  }

  const Scene& scene_;
  const std::string& path_;
  BufferBuilder buffer_;
};

}  // namespace

void writeGltf(const Scene& scene, const std::string& path) {
  GltfBuilder builder(scene, path);
  builder.validate();

  const std::filesystem::path target(path);
  std::vector<std::string> imageUris;
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const Texture& texture = scene.textures[i];
    const std::string uri = target.stem().string() + "_tex" + std::to_string(i) + ".png";
    writePng((target.parent_path() / uri).string(), texture.width, texture.height, texture.rgba8);
    imageUris.push_back(uri);
  }
  const std::string text = builder.build(imageUris).dump(1);

  const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw Error(path + ": cannot write '" + temporary + "': " + std::strerror(errno));
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw Error(path + ": cannot rename '" + temporary + "' into place: " + ec.message());
  }
}

}  // namespace engine
