// glTF 2.0 -> engine::Scene. tinygltf parses the JSON and the buffers; everything it hands back is
// treated as untrusted: every index is range-checked and every accessor is checked against its
// buffer before a byte is read, so malformed files end in an engine::Error, never a crash.
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "engine/error.h"
#include "engine/gltf.h"
#include "engine/image_io.h"
#include "gltf_draco.h"
#include "gltf_meshopt.h"
#include "gltf_preflight.h"
#include "gltf_scene_builder.h"

namespace engine {
namespace {

constexpr const char* kLightsExtension = "KHR_lights_punctual";

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Image decoding goes through OpenImageIO (engine::decodeTexture) rather than tinygltf's stb.
// The decoded textures are kept here, by glTF image index, instead of in tinygltf::Image, so the
// pixels are not copied twice.
struct ImageDecoder {
  std::string gltfPath;
  const tinygltf::Model* model = nullptr;  // filled by tinygltf before images are parsed
  std::vector<std::optional<Texture>> textures;
  gltf_detail::Preflight preflight;
  uint64_t textureBytes = 0;  // decoded so far
  std::string error;          // first failure, reported instead of tinygltf's wording
};

bool decodeImage(tinygltf::Image* image, const int imageIndex, std::string* err, std::string*, int,
                 int, const unsigned char* bytes, int size, void* userData) {
  auto& decoder = *static_cast<ImageDecoder*>(userData);
  const std::string label = "image " + std::to_string(imageIndex);
  try {
    if (imageIndex < 0) throw Error(label + ": invalid image index");
    const std::string name = image->uri.empty()
                                 ? std::filesystem::path(decoder.gltfPath).filename().string() +
                                       "#image" + std::to_string(imageIndex)
                                 : image->uri;
    std::span<const uint8_t> encoded;
    if (image->bufferView >= 0) {
      // tinygltf points into the buffer without checking that the view fits in it.
      const auto& views = decoder.model->bufferViews;
      if (static_cast<size_t>(image->bufferView) >= views.size()) {
        throw Error("bufferView " + std::to_string(image->bufferView) + " does not exist");
      }
      const tinygltf::BufferView& view = views[static_cast<size_t>(image->bufferView)];
      if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= decoder.model->buffers.size()) {
        throw Error("bufferView " + std::to_string(image->bufferView) + " has no valid buffer");
      }
      const auto& data = decoder.model->buffers[static_cast<size_t>(view.buffer)].data;
      if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
        throw Error("bufferView " + std::to_string(image->bufferView) +
                    " runs past the end of its buffer");
      }
      encoded = std::span<const uint8_t>(data.data() + view.byteOffset, view.byteLength);
    } else {
      if (bytes == nullptr || size <= 0) throw Error(name + ": empty image data");
      encoded = std::span<const uint8_t>(bytes, static_cast<size_t>(size));
    }
    // Decoded reduced towards the size the GPU keeps (kMaxTextureSize), read in strips: an 8192^2
    // texture never holds its full-size pixels in memory.
    const std::vector<bool>& colourImages = decoder.preflight.colourImages;
    const bool colour =
        size_t(imageIndex) < colourImages.size() && colourImages[size_t(imageIndex)];
    Texture texture = decodeTexture(name, encoded, {kMaxTextureSize, colour});
    decoder.textureBytes += texture.rgba8.size();
    if (decoder.preflight.bufferBytes + decoder.textureBytes > kMaxSceneBytes)
      throw Error("buffers and textures decoded so far hold " +
                  std::to_string((decoder.preflight.bufferBytes + decoder.textureBytes) >> 20) +
                  " MB, more than the " + std::to_string(kMaxSceneBytes >> 20) +
                  " MB a scene may use (engine::kMaxSceneBytes)");
    texture.name = name;
    const auto slot = static_cast<size_t>(imageIndex);
    if (decoder.textures.size() <= slot) decoder.textures.resize(slot + 1);
    decoder.textures[slot] = std::move(texture);
    return true;
  } catch (const std::exception& e) {
    if (decoder.error.empty()) decoder.error = label + ": " + joinLines(e.what());
    if (err != nullptr) *err += decoder.error + "\n";
    return false;
  }
}

}  // namespace

namespace gltf_detail {

void SceneBuilder::build() {
  // A required extension the loader cannot read was refused by gltf_detail::preflight. An
  // optional one's data has a fallback the file must also carry; the loader reads that.
  for (const std::string& extension : model_.extensionsUsed)
    if (!understoodExtension(extension))
      scene_.warnings.push_back(
          located("ignores extension '" + extension + "' (the loader does not read it)"));
  convertMaterials();
  convertLights();
  convertCameras();
  traverseNodes();
  if (scene_.indices.empty())
    fail("scene has no triangles" +
         std::string(scene_.warnings.empty() ? "" : " (" + scene_.warnings.front() + ")"));
  if (defaultMaterial_) scene_.materials.push_back(*defaultMaterial_);
}

glm::dmat4 SceneBuilder::localMatrix(const tinygltf::Node& node, const std::string& where) const {
  auto checkFinite = [&](const std::vector<double>& values, const char* field) {
    for (double v : values) {
      if (!std::isfinite(v)) fail(where + ": " + field + " has non-finite values");
    }
  };
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) fail(where + ": matrix must have 16 values");
    checkFinite(node.matrix, "matrix");
    glm::dmat4 m(1.0);
    for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = node.matrix[static_cast<size_t>(i)];
    return m;  // glTF stores column-major, as GLM indexes
  }
  glm::dmat4 m(1.0);
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) fail(where + ": translation must have 3 values");
    checkFinite(node.translation, "translation");
    m[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) fail(where + ": rotation must have 4 values");
    checkFinite(node.rotation, "rotation");
    // glTF quaternions are (x, y, z, w); renormalised because exporters round them.
    glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    const double length = glm::length(q);
    if (!(length > 0.0)) fail(where + ": rotation quaternion is zero");
    m = m * glm::dmat4(glm::mat3_cast(q / length));
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) fail(where + ": scale must have 3 values");
    checkFinite(node.scale, "scale");
    m[0] *= node.scale[0];
    m[1] *= node.scale[1];
    m[2] *= node.scale[2];
  }
  return m;
}

std::vector<int> SceneBuilder::rootNodes() const {
  if (!model_.scenes.empty()) {
    int sceneIndex = model_.defaultScene;
    if (sceneIndex < 0) sceneIndex = 0;
    return at(model_.scenes, sceneIndex, "scene", "default scene").nodes;
  }
  // No scenes: every node that is nobody's child is a root.
  std::vector<bool> isChild(model_.nodes.size(), false);
  for (const tinygltf::Node& node : model_.nodes) {
    for (int child : node.children) {
      if (child >= 0 && static_cast<size_t>(child) < isChild.size()) {
        isChild[static_cast<size_t>(child)] = true;
      }
    }
  }
  std::vector<int> roots;
  for (size_t i = 0; i < isChild.size(); ++i) {
    if (!isChild[i]) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

// Depth-first, children in file order, with an explicit stack so that deep hierarchies cannot
// overflow the call stack. glTF node hierarchies are forests: a node reached twice is an error
// (it also stops cycles).
void SceneBuilder::traverseNodes() {
  struct Pending {
    int node;
    glm::dmat4 parentToWorld;
  };
  std::vector<Pending> stack;
  const std::vector<int> roots = rootNodes();
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0)});
  std::vector<bool> visited(model_.nodes.size(), false);
  while (!stack.empty()) {
    const Pending pending = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = at(model_.nodes, pending.node, "node", "node hierarchy");
    const auto nodeIndex = static_cast<size_t>(pending.node);
    const std::string where = label("node", node.name, nodeIndex);
    if (visited[nodeIndex]) fail(where + " is reached twice (the node hierarchy must be a tree)");
    visited[nodeIndex] = true;
    const glm::dmat4 world = pending.parentToWorld * localMatrix(node, where);
    if (node.mesh >= 0) addMesh(node.mesh, world, where);
    if (node.camera >= 0) addCamera(node.camera, world, where);
    addLight(node, world, where);
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
      stack.push_back({*it, world});
    }
  }
}

void SceneBuilder::addCamera(int cameraIndex, const glm::dmat4& world, const std::string& where) {
  Camera camera = at(cameras_, cameraIndex, "camera", where);
  // The node's world matrix as floats first: a .gltf written from a camera (vsgl_viewer's
  // screenshots) then reads back bit for bit.
  const std::optional<glm::mat4> frame = rigidCameraFrame(glm::mat4(world));
  if (!frame) fail(where + ": camera node has a degenerate transform");
  camera.cameraToWorld = *frame;
  scene_.cameras.push_back(std::move(camera));
}

void SceneBuilder::addLight(const tinygltf::Node& node, const glm::dmat4& world,
                            const std::string& where) {
  const auto ext = node.extensions.find(kLightsExtension);
  if (ext == node.extensions.end()) return;
  const tinygltf::Value& value = ext->second;
  if (!value.IsObject() || !value.Has("light") || !value.Get("light").IsNumber()) {
    fail(where + ": KHR_lights_punctual needs an integer 'light'");
  }
  const double index = value.Get("light").GetNumberAsDouble();
  if (index != std::floor(index) || std::abs(index) > 1e9) {
    fail(where + ": KHR_lights_punctual 'light' must be an integer");
  }
  Light light = at(lights_, static_cast<int>(index), "light", where);
  light.position = glm::vec3(world[3]);
  // -Z of the node's world matrix as floats, kept as written when it is a unit vector: a light
  // written by writeGltf reads back with the same direction to the bit.
  const auto direction =
      fileLightDirection(glm::vec3(glm::mat4(world) * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)));
  if (!direction) fail(where + ": light node has a degenerate transform");
  light.direction = *direction;
  scene_.lights.push_back(std::move(light));
}

}  // namespace gltf_detail

Scene loadGltf(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".gltf" && ext != ".glb") {
    throw Error(path + ": unsupported file extension '" + ext + "' (expected .gltf or .glb)");
  }
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": file not found");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": not a regular file");

  tinygltf::Model model;
  ImageDecoder decoder;
  const std::string jsonText = gltf_detail::jsonText(path, ext == ".glb");
  decoder.preflight = gltf_detail::preflight(path, jsonText);
  decoder.gltfPath = path;
  decoder.model = &model;
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&decodeImage, &decoder);
  parser.SetFsCallbacks(gltf_detail::regularFilesOnly());
  std::string err;
  std::string warn;
  bool ok = false;
  try {
    // Compressed files hold what tinygltf refuses (a Draco primitive's index accessor without a
    // bufferView, a meshopt fallback buffer without data): they are parsed from their edited
    // JSON (gltf_draco.h, gltf_meshopt.h).
    nlohmann::json doc = nlohmann::json::parse(jsonText, nullptr, false);
    const bool edited =
        !doc.is_discarded() && (gltf_detail::stashDracoIndices(doc) |
                                gltf_detail::giveFallbackBuffersData(doc, ext == ".glb"));
    const std::string json = edited ? doc.dump() : std::string();
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    if (json.empty()) {
      ok = ext == ".glb" ? parser.LoadBinaryFromFile(&model, &err, &warn, path)
                         : parser.LoadASCIIFromFile(&model, &err, &warn, path);
    } else if (ext == ".glb") {
      const std::vector<unsigned char> glb = gltf_detail::glbWithJson(path, json);
      ok = parser.LoadBinaryFromMemory(&model, &err, &warn, glb.data(),
                                       static_cast<unsigned int>(glb.size()), baseDir);
    } else {
      ok = parser.LoadASCIIFromString(&model, &err, &warn, json.data(),
                                      static_cast<unsigned int>(json.size()), baseDir);
    }
  } catch (const std::exception& e) {
    // tinygltf reports JSON syntax errors in `err`; this catches anything else it throws.
    throw Error(path + ": malformed glTF: " + joinLines(e.what()));
  }
  if (!decoder.error.empty()) throw Error(path + ": " + decoder.error);
  if (!ok) {
    const std::string reason = joinLines(err.empty() ? warn : err);
    throw Error(path + ": " + (reason.empty() ? "cannot parse glTF" : reason));
  }
  // tinygltf only warns when an external image file is missing or unreadable.
  decoder.textures.resize(model.images.size());
  Scene scene;
  scene.source = path;
  for (size_t i = 0; i < model.images.size(); ++i) {
    if (!decoder.textures[i]) {
      throw Error(path + ": image " + std::to_string(i) + ": cannot read texture file '" +
                  model.images[i].uri + "'");
    }
    scene.textures.push_back(std::move(*decoder.textures[i]));
  }
  const uint64_t budget = kMaxSceneBytes - decoder.preflight.bufferBytes - decoder.textureBytes;
  const uint64_t meshoptBytes = gltf_detail::decodeMeshoptViews(path, model, budget);
  gltf_detail::decodeDracoPrimitives(path, model, budget - meshoptBytes);
  gltf_detail::SceneBuilder(path, model, scene).build();
  return scene;
}

}  // namespace engine
