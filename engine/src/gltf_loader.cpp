// glTF 2.0 -> engine::Scene. tinygltf parses the JSON and the buffers; everything it hands back is
// treated as untrusted: every index is range-checked and every accessor is checked against its
// buffer before a byte is read, so malformed files end in an engine::Error, never a crash.
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "engine/error.h"
#include "engine/gltf.h"
#include "engine/image_io.h"

namespace engine {
namespace {

constexpr const char* kLightsExtension = "KHR_lights_punctual";
// Extensions a file may list as required. Emissive strength only scales emission, which this
// module ignores anyway (see scene.h).
constexpr std::string_view kUnderstoodExtensions[] = {"KHR_lights_punctual",
                                                      "KHR_materials_emissive_strength"};

// tinygltf reports several problems as newline-separated lines; our errors are one line.
std::string oneLine(const std::string& text) {
  std::string out;
  bool pendingSeparator = false;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      pendingSeparator = !out.empty();
      continue;
    }
    if (pendingSeparator) {
      out += "; ";
      pendingSeparator = false;
    }
    out += c;
  }
  return out;
}

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
  std::string error;  // first failure, reported instead of tinygltf's wording
};

bool decodeImage(tinygltf::Image* image, const int imageIndex, std::string* err, std::string*,
                 int, int, const unsigned char* bytes, int size, void* userData) {
  auto& decoder = *static_cast<ImageDecoder*>(userData);
  const std::string label = "image " + std::to_string(imageIndex);
  try {
    if (imageIndex < 0) throw Error(label + ": invalid image index");
    const std::string name =
        image->uri.empty()
            ? std::filesystem::path(decoder.gltfPath).filename().string() + "#image" +
                  std::to_string(imageIndex)
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
    Texture texture = decodeTexture(name, encoded);
    texture.name = name;
    const auto slot = static_cast<size_t>(imageIndex);
    if (decoder.textures.size() <= slot) decoder.textures.resize(slot + 1);
    decoder.textures[slot] = std::move(texture);
    return true;
  } catch (const std::exception& e) {
    if (decoder.error.empty()) decoder.error = label + ": " + oneLine(e.what());
    if (err != nullptr) *err += decoder.error + "\n";
    return false;
  }
}

// One accessor's elements, checked to lie inside its buffer.
struct AccessorView {
  const uint8_t* data = nullptr;  // first element
  size_t count = 0;
  size_t stride = 0;  // bytes between elements
  int componentType = 0;
  bool normalized = false;
};

size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

size_t componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    default:
      return 0;
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    default:
      return "a matrix or unknown type";
  }
}

template <typename T>
T loadUnaligned(const uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

// Component c of element i as float; normalized integers map to [0, 1] or [-1, 1] (glTF 3.11).
float readFloat(const AccessorView& view, size_t i, size_t c) {
  const uint8_t* p = view.data + i * view.stride + c * componentSize(view.componentType);
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return loadUnaligned<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return static_cast<float>(p[0]) / (view.normalized ? 255.0f : 1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return static_cast<float>(loadUnaligned<uint16_t>(p)) / (view.normalized ? 65535.0f : 1.0f);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = static_cast<float>(loadUnaligned<int8_t>(p));
      return view.normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float v = static_cast<float>(loadUnaligned<int16_t>(p));
      return view.normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    default:
      return 0.0f;  // unreachable: viewAccessor() admits only the types above
  }
}

uint32_t readIndex(const AccessorView& view, size_t i) {
  const uint8_t* p = view.data + i * view.stride;
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return loadUnaligned<uint16_t>(p);
    default:
      return loadUnaligned<uint32_t>(p);
  }
}

bool isFinite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Unit vector, or nullopt when v is zero or not finite.
std::optional<glm::dvec3> tryNormalize(const glm::dvec3& v) {
  const double length = glm::length(v);
  if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
  return v / length;
}

// Converts the tinygltf model into a Scene; every problem becomes Error("<path>: <problem>").
class SceneBuilder {
 public:
  SceneBuilder(const std::string& path, const tinygltf::Model& model, Scene& scene)
      : path_(path), model_(model), scene_(scene) {}

  void build() {
    for (const std::string& extension : model_.extensionsRequired) {
      if (std::find(std::begin(kUnderstoodExtensions), std::end(kUnderstoodExtensions),
                    extension) == std::end(kUnderstoodExtensions)) {
        fail("requires unsupported extension '" + extension + "'");
      }
    }
    convertMaterials();
    convertLights();
    convertCameras();
    traverseNodes();
    if (scene_.indices.empty()) fail("scene has no triangles");
    if (scene_.lights.empty()) fail("scene has no lights (KHR_lights_punctual)");
    if (defaultMaterial_) scene_.materials.push_back(*defaultMaterial_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw Error(path_ + ": " + problem); }

  template <typename T>
  const T& at(const std::vector<T>& items, int index, const std::string& kind,
              const std::string& where) const {
    if (index < 0 || static_cast<size_t>(index) >= items.size()) {
      fail(where + ": " + kind + " " + std::to_string(index) + " does not exist");
    }
    return items[static_cast<size_t>(index)];
  }

  static std::string label(const std::string& kind, const std::string& name, size_t index) {
    return name.empty() ? kind + " " + std::to_string(index) : kind + " '" + name + "'";
  }

  // Maps a glTF texture to the Scene::textures index of its source image.
  int textureImage(const tinygltf::TextureInfo& info, const std::string& where) const {
    if (info.index < 0) return -1;
    if (info.texCoord != 0) {
      fail(where + " uses TEXCOORD_" + std::to_string(info.texCoord) +
           " (only TEXCOORD_0 is supported)");
    }
    const tinygltf::Texture& texture = at(model_.textures, info.index, "texture", where);
    if (texture.source < 0) {
      fail(where + ": texture " + std::to_string(info.index) +
           " has no source image (image extensions are not supported)");
    }
    at(model_.images, texture.source, "image", where + ": texture " + std::to_string(info.index));
    return texture.source;
  }

  static bool inUnitRange(double v) { return v >= 0.0 && v <= 1.0; }

  void convertMaterials() {
    for (size_t m = 0; m < model_.materials.size(); ++m) {
      const tinygltf::Material& in = model_.materials[m];
      const tinygltf::PbrMetallicRoughness& pbr = in.pbrMetallicRoughness;
      const std::string where = label("material", in.name, m);
      Material out;
      out.name = in.name;
      if (pbr.baseColorFactor.size() != 4) fail(where + ": baseColorFactor must have 4 values");
      for (int c = 0; c < 4; ++c) {
        const double v = pbr.baseColorFactor[static_cast<size_t>(c)];
        if (!inUnitRange(v)) fail(where + ": baseColorFactor values must lie in [0, 1]");
        out.baseColorFactor[c] = static_cast<float>(v);
      }
      if (!inUnitRange(pbr.metallicFactor)) fail(where + ": metallicFactor must lie in [0, 1]");
      if (!inUnitRange(pbr.roughnessFactor)) fail(where + ": roughnessFactor must lie in [0, 1]");
      out.metallicFactor = static_cast<float>(pbr.metallicFactor);
      out.roughnessFactor = static_cast<float>(pbr.roughnessFactor);
      out.baseColorTexture = textureImage(pbr.baseColorTexture, where + " baseColorTexture");
      out.metallicRoughnessTexture =
          textureImage(pbr.metallicRoughnessTexture, where + " metallicRoughnessTexture");
      out.doubleSided = in.doubleSided;
      scene_.materials.push_back(std::move(out));
    }
  }

  void convertLights() {
    for (size_t l = 0; l < model_.lights.size(); ++l) {
      const tinygltf::Light& in = model_.lights[l];
      const std::string where = label("light", in.name, l);
      Light out;
      out.name = in.name;
      if (in.type == "directional") {
        out.type = LightType::Directional;
      } else if (in.type == "point") {
        out.type = LightType::Point;
      } else if (in.type == "spot") {
        out.type = LightType::Spot;
      } else {
        fail(where + ": unknown light type '" + in.type + "'");
      }
      if (!in.color.empty()) {
        if (in.color.size() != 3) fail(where + ": color must have 3 values");
        for (int c = 0; c < 3; ++c) {
          const double v = in.color[static_cast<size_t>(c)];
          if (!(v >= 0.0) || !std::isfinite(v)) fail(where + ": color values must be >= 0");
          out.color[c] = static_cast<float>(v);
        }
      }
      if (!(in.intensity >= 0.0) || !std::isfinite(in.intensity)) {
        fail(where + ": intensity must be >= 0");
      }
      if (!(in.range >= 0.0) || !std::isfinite(in.range)) fail(where + ": range must be >= 0");
      out.intensity = static_cast<float>(in.intensity);
      out.range = static_cast<float>(in.range);
      if (out.type == LightType::Spot) {
        const double inner = in.spot.innerConeAngle;
        const double outer = in.spot.outerConeAngle;
        if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2)) {
          fail(where + ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= "
                       "pi/2 (got innerConeAngle " +
               std::to_string(inner) + ", outerConeAngle " + std::to_string(outer) + ")");
        }
        out.innerConeAngle = static_cast<float>(inner);
        out.outerConeAngle = static_cast<float>(outer);
      }
      lights_.push_back(std::move(out));
    }
  }

  void convertCameras() {
    for (size_t c = 0; c < model_.cameras.size(); ++c) {
      const tinygltf::Camera& in = model_.cameras[c];
      const std::string where = label("camera", in.name, c);
      Camera out;
      out.name = in.name;
      if (in.type == "perspective") {
        const tinygltf::PerspectiveCamera& p = in.perspective;
        if (!(p.yfov > 0.0 && p.yfov < std::numbers::pi)) fail(where + ": yfov must be in (0, pi)");
        if (!(p.znear > 0.0) || !std::isfinite(p.znear)) fail(where + ": znear must be > 0");
        if (!(p.zfar == 0.0 || p.zfar > p.znear) || !std::isfinite(p.zfar)) {
          fail(where + ": zfar must be > znear (or absent for an infinite projection)");
        }
        if (!(p.aspectRatio >= 0.0) || !std::isfinite(p.aspectRatio)) {
          fail(where + ": aspectRatio must be > 0");
        }
        out.perspective = true;
        out.yfov = static_cast<float>(p.yfov);
        out.aspectRatio = static_cast<float>(p.aspectRatio);
        out.znear = static_cast<float>(p.znear);
        out.zfar = static_cast<float>(p.zfar);
      } else if (in.type == "orthographic") {
        const tinygltf::OrthographicCamera& o = in.orthographic;
        if (!(o.xmag != 0.0 && o.ymag != 0.0) || !std::isfinite(o.xmag) ||
            !std::isfinite(o.ymag)) {
          fail(where + ": xmag and ymag must be non-zero");
        }
        if (!(o.znear >= 0.0) || !(o.zfar > o.znear) || !std::isfinite(o.zfar)) {
          fail(where + ": orthographic znear must be >= 0 and zfar > znear");
        }
        out.perspective = false;
        out.xmag = static_cast<float>(std::abs(o.xmag));
        out.ymag = static_cast<float>(std::abs(o.ymag));
        out.znear = static_cast<float>(o.znear);
        out.zfar = static_cast<float>(o.zfar);
      } else {
        fail(where + ": unknown camera type '" + in.type + "'");
      }
      cameras_.push_back(std::move(out));
    }
  }

  glm::dmat4 localMatrix(const tinygltf::Node& node, const std::string& where) const {
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

  std::vector<int> rootNodes() const {
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
  void traverseNodes() {
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

  void addCamera(int cameraIndex, const glm::dmat4& world, const std::string& where) {
    Camera camera = at(cameras_, cameraIndex, "camera", where);
    // Scale (and a mirror) would skew the view: keep the viewing axis -Z exact, then make Y
    // orthogonal to it and X = Y x Z, a right-handed orthonormal frame.
    const auto z = tryNormalize(glm::dvec3(world[2]));
    const auto y = z ? tryNormalize(glm::dvec3(world[1]) - glm::dot(glm::dvec3(world[1]), *z) * *z)
                     : std::nullopt;
    if (!z || !y) fail(where + ": camera node has a degenerate transform");
    const glm::dvec3 x = glm::cross(*y, *z);
    camera.cameraToWorld = glm::mat4(glm::dmat4(glm::dvec4(x, 0.0), glm::dvec4(*y, 0.0),
                                                glm::dvec4(*z, 0.0), world[3]));
    scene_.cameras.push_back(std::move(camera));
  }

  void addLight(const tinygltf::Node& node, const glm::dmat4& world, const std::string& where) {
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
    const auto direction = tryNormalize(glm::dvec3(world * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
    if (!direction) fail(where + ": light node has a degenerate transform");
    light.direction = glm::vec3(*direction);
    scene_.lights.push_back(std::move(light));
  }

  AccessorView viewAccessor(int accessorIndex, const std::string& where, int expectedType,
                            std::initializer_list<int> allowedComponentTypes) const {
    const tinygltf::Accessor& accessor = at(model_.accessors, accessorIndex, "accessor", where);
    const std::string what = where + " (accessor " + std::to_string(accessorIndex) + ")";
    if (accessor.sparse.isSparse) fail(what + ": sparse accessors are not supported");
    if (accessor.type != expectedType) {
      fail(what + ": expected type " + typeName(expectedType) + ", got " +
           typeName(accessor.type));
    }
    if (std::find(allowedComponentTypes.begin(), allowedComponentTypes.end(),
                  accessor.componentType) == allowedComponentTypes.end()) {
      fail(what + ": unsupported componentType " + std::to_string(accessor.componentType));
    }
    if (accessor.bufferView < 0) fail(what + ": accessors without a bufferView are not supported");
    const tinygltf::BufferView& view = at(model_.bufferViews, accessor.bufferView, "bufferView", what);
    const auto& data = at(model_.buffers, view.buffer, "buffer", what).data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
      fail(what + ": bufferView " + std::to_string(accessor.bufferView) +
           " runs past the end of buffer " + std::to_string(view.buffer) + " (" +
           std::to_string(data.size()) + " bytes)");
    }
    const size_t elementSize = componentSize(accessor.componentType) * componentCount(expectedType);
    const size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize) fail(what + ": byteStride is smaller than one element");
    // The last element must end inside the view: offset + stride * (count - 1) + elementSize,
    // compared by division so that a huge count cannot overflow.
    if (accessor.count > 0) {
      const bool fits = accessor.byteOffset <= view.byteLength &&
                        elementSize <= view.byteLength - accessor.byteOffset &&
                        accessor.count - 1 <=
                            (view.byteLength - accessor.byteOffset - elementSize) / stride;
      if (!fits) {
        fail(what + ": " + std::to_string(accessor.count) + " elements at byteOffset " +
             std::to_string(accessor.byteOffset) + " do not fit in bufferView " +
             std::to_string(accessor.bufferView) + " (" + std::to_string(view.byteLength) +
             " bytes)");
      }
    }
    AccessorView out;
    out.data = data.data() + view.byteOffset + accessor.byteOffset;
    out.count = accessor.count;
    out.stride = stride;
    out.componentType = accessor.componentType;
    out.normalized = accessor.normalized;
    return out;
  }

  uint32_t materialFor(const tinygltf::Primitive& primitive, const std::string& where) {
    if (primitive.material >= 0) {
      at(model_.materials, primitive.material, "material", where);
      return static_cast<uint32_t>(primitive.material);
    }
    if (!defaultMaterial_) {
      defaultMaterial_ = Material{};
      defaultMaterial_->name = "default";
      defaultMaterial_->metallicFactor = 0.0f;
      defaultMaterial_->roughnessFactor = 0.5f;
    }
    // Appended after all glTF materials once the whole scene is read.
    return static_cast<uint32_t>(model_.materials.size());
  }

  void addMesh(int meshIndex, const glm::dmat4& world, const std::string& nodeWhere) {
    const tinygltf::Mesh& mesh = at(model_.meshes, meshIndex, "mesh", nodeWhere);
    const std::string meshWhere = label("mesh", mesh.name, static_cast<size_t>(meshIndex));
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      addPrimitive(mesh.primitives[p], world, meshWhere + " primitive " + std::to_string(p));
    }
  }

  // Vertex order of the primitive's triangles, as indices local to the primitive.
  static std::vector<uint32_t> assembleTriangles(int mode, const std::vector<uint32_t>& corners) {
    std::vector<uint32_t> triangles;
    if (mode == TINYGLTF_MODE_TRIANGLES) return corners;
    if (corners.size() < 3) return triangles;
    triangles.reserve((corners.size() - 2) * 3);
    for (size_t i = 0; i + 2 < corners.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // glTF 2.0 spec 3.7.2.1: odd triangles swap two corners to keep the winding.
        const size_t odd = i % 2;
        triangles.insert(triangles.end(),
                         {corners[i], corners[i + 1 + odd], corners[i + 2 - odd]});
      } else {
        triangles.insert(triangles.end(), {corners[i + 1], corners[i + 2], corners[0]});
      }
    }
    return triangles;
  }

  void addPrimitive(const tinygltf::Primitive& primitive, const glm::dmat4& world,
                    const std::string& where) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      fail(where + ": unsupported primitive mode " + std::to_string(mode) + " (only triangles)");
    }
    const auto attribute = [&](const char* name) {
      const auto it = primitive.attributes.find(name);
      return it == primitive.attributes.end() ? -1 : it->second;
    };
    const int positionAccessor = attribute("POSITION");
    if (positionAccessor < 0) fail(where + ": no POSITION attribute");
    const AccessorView positions = viewAccessor(positionAccessor, where + " POSITION",
                                                TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const size_t vertexCount = positions.count;
    std::optional<AccessorView> normals;
    if (const int a = attribute("NORMAL"); a >= 0) {
      normals = viewAccessor(a, where + " NORMAL", TINYGLTF_TYPE_VEC3,
                             {TINYGLTF_COMPONENT_TYPE_FLOAT});
    }
    std::optional<AccessorView> uvs;
    if (const int a = attribute("TEXCOORD_0"); a >= 0) {
      uvs = viewAccessor(a, where + " TEXCOORD_0", TINYGLTF_TYPE_VEC2,
                         {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
      if (uvs->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !uvs->normalized) {
        fail(where + " TEXCOORD_0: integer texture coordinates must be normalized");
      }
    }
    if ((normals && normals->count != vertexCount) || (uvs && uvs->count != vertexCount)) {
      fail(where + ": NORMAL/TEXCOORD_0 counts differ from the POSITION count " +
           std::to_string(vertexCount));
    }

    std::vector<uint32_t> corners;
    if (primitive.indices >= 0) {
      const AccessorView indices =
          viewAccessor(primitive.indices, where + " indices", TINYGLTF_TYPE_SCALAR,
                       {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
      corners.resize(indices.count);
      for (size_t i = 0; i < indices.count; ++i) {
        corners[i] = readIndex(indices, i);
        if (corners[i] >= vertexCount) {
          fail(where + ": index " + std::to_string(corners[i]) + " at position " +
               std::to_string(i) + " is out of range (" + std::to_string(vertexCount) +
               " vertices)");
        }
      }
    } else {
      if (vertexCount > std::numeric_limits<uint32_t>::max()) fail(where + ": too many vertices");
      corners.resize(vertexCount);
      for (size_t i = 0; i < vertexCount; ++i) corners[i] = static_cast<uint32_t>(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && corners.size() % 3 != 0) {
      fail(where + ": triangle list with " + std::to_string(corners.size()) +
           " corners (not a multiple of 3)");
    }
    std::vector<uint32_t> triangles = assembleTriangles(mode, corners);

    const size_t base = scene_.positions.size();
    if (vertexCount > std::numeric_limits<uint32_t>::max() - base) {
      fail(where + ": the scene has more than 2^32 vertices");
    }
    const uint32_t material = materialFor(primitive, where);

    // World-space positions; normals by the inverse-transpose, which keeps them perpendicular to
    // the surface under non-uniform scale.
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    std::vector<glm::vec3> worldPositions(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v) {
      const glm::dvec3 local(readFloat(positions, v, 0), readFloat(positions, v, 1),
                             readFloat(positions, v, 2));
      const glm::dvec3 p = glm::dvec3(world * glm::dvec4(local, 1.0));
      if (!isFinite(p)) fail(where + " POSITION: non-finite position at vertex " + std::to_string(v));
      worldPositions[v] = glm::vec3(p);
    }
    // A mirroring transform turns counter-clockwise triangles clockwise: swap two corners.
    if (glm::determinant(glm::dmat3(world)) < 0.0) {
      for (size_t t = 0; t + 2 < triangles.size(); t += 3) std::swap(triangles[t + 1], triangles[t + 2]);
    }

    // Face normals (unnormalised: length = twice the area) of the final, world-space winding.
    // Each vertex remembers one non-degenerate face as the fallback for a zero normal.
    std::vector<glm::dvec3> fallback(vertexCount, glm::dvec3(0.0, 1.0, 0.0));
    std::vector<bool> hasFallback(vertexCount, false);
    std::vector<glm::dvec3> faceNormals(triangles.size() / 3);
    for (size_t t = 0; t < faceNormals.size(); ++t) {
      const glm::dvec3 p0(worldPositions[triangles[3 * t]]);
      const glm::dvec3 p1(worldPositions[triangles[3 * t + 1]]);
      const glm::dvec3 p2(worldPositions[triangles[3 * t + 2]]);
      faceNormals[t] = glm::cross(p1 - p0, p2 - p0);
      if (const auto unit = tryNormalize(faceNormals[t])) {
        for (size_t k = 0; k < 3; ++k) {
          const uint32_t v = triangles[3 * t + k];
          if (!hasFallback[v]) {
            fallback[v] = *unit;
            hasFallback[v] = true;
          }
        }
      }
    }

    std::vector<glm::dvec3> vertexNormals(vertexCount, glm::dvec3(0.0));
    if (normals) {
      for (size_t v = 0; v < vertexCount; ++v) {
        const glm::dvec3 n(readFloat(*normals, v, 0), readFloat(*normals, v, 1),
                           readFloat(*normals, v, 2));
        vertexNormals[v] = normalMatrix * n;
      }
    } else {
      // Area-weighted smooth normals: vertices at exactly the same position share one sum.
      std::vector<uint32_t> order(vertexCount);
      for (size_t v = 0; v < vertexCount; ++v) order[v] = static_cast<uint32_t>(v);
      const auto less = [&](uint32_t a, uint32_t b) {
        const glm::vec3& pa = worldPositions[a];
        const glm::vec3& pb = worldPositions[b];
        if (pa.x != pb.x) return pa.x < pb.x;
        if (pa.y != pb.y) return pa.y < pb.y;
        return pa.z < pb.z;
      };
      std::sort(order.begin(), order.end(), less);
      std::vector<uint32_t> group(vertexCount, 0);
      uint32_t groupCount = 0;
      for (size_t i = 0; i < order.size(); ++i) {
        if (i > 0 && less(order[i - 1], order[i])) ++groupCount;
        group[order[i]] = groupCount;
      }
      std::vector<glm::dvec3> sums(vertexCount == 0 ? 0 : groupCount + 1, glm::dvec3(0.0));
      for (size_t t = 0; t < faceNormals.size(); ++t) {
        for (size_t k = 0; k < 3; ++k) sums[group[triangles[3 * t + k]]] += faceNormals[t];
      }
      for (size_t v = 0; v < vertexCount; ++v) vertexNormals[v] = sums[group[v]];
    }

    scene_.positions.insert(scene_.positions.end(), worldPositions.begin(), worldPositions.end());
    for (size_t v = 0; v < vertexCount; ++v) {
      scene_.normals.emplace_back(tryNormalize(vertexNormals[v]).value_or(fallback[v]));
      scene_.uvs.emplace_back(uvs ? glm::vec2(readFloat(*uvs, v, 0), readFloat(*uvs, v, 1))
                                  : glm::vec2(0.0f));
    }
    for (uint32_t corner : triangles) scene_.indices.push_back(static_cast<uint32_t>(base) + corner);
    scene_.triangleMaterial.insert(scene_.triangleMaterial.end(), triangles.size() / 3, material);
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  Scene& scene_;
  std::vector<Light> lights_;    // model.lights, validated; instanced by nodes
  std::vector<Camera> cameras_;  // model.cameras, validated; instanced by nodes
  std::optional<Material> defaultMaterial_;
};

}  // namespace

Scene loadGltf(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".gltf" && ext != ".glb") {
    throw Error(path + ": unsupported file extension '" + ext + "' (expected .gltf or .glb)");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": file not found");

  tinygltf::Model model;
  ImageDecoder decoder;
  decoder.gltfPath = path;
  decoder.model = &model;
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&decodeImage, &decoder);
  std::string err;
  std::string warn;
  bool ok = false;
  try {
    ok = ext == ".glb" ? parser.LoadBinaryFromFile(&model, &err, &warn, path)
                       : parser.LoadASCIIFromFile(&model, &err, &warn, path);
  } catch (const std::exception& e) {
    // tinygltf reports JSON syntax errors in `err`; this catches anything else it throws.
    throw Error(path + ": malformed glTF: " + oneLine(e.what()));
  }
  if (!decoder.error.empty()) throw Error(path + ": " + decoder.error);
  if (!ok) {
    const std::string reason = oneLine(err.empty() ? warn : err);
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
  SceneBuilder(path, model, scene).build();
  return scene;
}

}  // namespace engine
