#include "gltf_draco.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <span>
#include <utility>
#include <vector>

#include "draco_decoder.h"
#include "engine/error.h"

namespace engine::gltf_detail {
namespace {

constexpr const char* kStashedIndices = "vsgl:indices";

void appendU32(std::vector<unsigned char>& out, uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(value >> (8 * i)));
}

class DracoPrimitives {
 public:
  DracoPrimitives(const std::string& path, tinygltf::Model& model, uint64_t budgetBytes)
      : path_(path), model_(model), budget_(budgetBytes) {}

  void decode(tinygltf::Primitive& primitive, const std::string& where) {
    const auto extension = primitive.extensions.find("KHR_draco_mesh_compression");
    if (extension == primitive.extensions.end()) return;
    const tinygltf::Value& ext = extension->second;
    if (!ext.IsObject() || !ext.Has("bufferView") || !ext.Get("bufferView").IsInt())
      fail(where, "KHR_draco_mesh_compression needs an integer 'bufferView'");
    const tinygltf::Value& ids = ext.Get("attributes");
    if (!ids.IsObject()) fail(where, "KHR_draco_mesh_compression needs an 'attributes' object");

    // The attributes to read: each accessor with the component count of its type.
    std::vector<std::pair<int, int>> wanted;
    std::vector<int> accessors;
    for (const std::string& name : ids.Keys()) {
      const auto attribute = primitive.attributes.find(name);
      if (attribute == primitive.attributes.end())
        fail(where, "Draco attribute '" + name + "' is not among the primitive's attributes");
      if (!ids.Get(name).IsInt())
        fail(where, "Draco attribute '" + name + "' id is not an integer");
      const tinygltf::Accessor& target = accessor(attribute->second, where);
      wanted.emplace_back(ids.Get(name).Get<int>(),
                          tinygltf::GetNumComponentsInType(static_cast<uint32_t>(target.type)));
      accessors.push_back(attribute->second);
    }

    // stashDracoIndices moved the file's index accessor here.
    if (ext.Has(kStashedIndices) && ext.Get(kStashedIndices).IsInt())
      primitive.indices = ext.Get(kStashedIndices).Get<int>();

    draco_decoder::Mesh mesh;
    const std::string problem = draco_decoder::decode(
        bitstream(ext.Get("bufferView").Get<int>(), where), wanted, budget_, mesh);
    if (!problem.empty()) fail(where, problem);

    if (primitive.indices < 0) {
      primitive.indices = static_cast<int>(model_.accessors.size());
      tinygltf::Accessor indices;
      indices.type = TINYGLTF_TYPE_SCALAR;
      indices.count = mesh.corners.size();
      model_.accessors.push_back(indices);
    }
    replaceData(accessor(primitive.indices, where), mesh.corners,
                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, "indices", where);
    for (size_t a = 0; a < accessors.size(); ++a) {
      tinygltf::Accessor& target = accessor(accessors[a], where);
      if (target.count != mesh.points)
        fail(where, "accessor " + std::to_string(accessors[a]) + " has count " +
                        std::to_string(target.count) + ", the Draco mesh " +
                        std::to_string(mesh.points) + " points");
      replaceData(target, mesh.attributes[a].values, TINYGLTF_COMPONENT_TYPE_FLOAT,
                  "accessor " + std::to_string(accessors[a]), where);
    }
    primitive.extensions.erase(extension);
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw Error(path_ + ": " + where + ": " + problem);
  }

  tinygltf::Accessor& accessor(int index, const std::string& where) {
    if (index < 0 || size_t(index) >= model_.accessors.size())
      fail(where, "accessor " + std::to_string(index) + " does not exist");
    return model_.accessors[size_t(index)];
  }

  std::span<const uint8_t> bitstream(int viewIndex, const std::string& where) const {
    const std::string view = "Draco bufferView " + std::to_string(viewIndex);
    if (viewIndex < 0 || size_t(viewIndex) >= model_.bufferViews.size())
      fail(where, view + " does not exist");
    const tinygltf::BufferView& v = model_.bufferViews[size_t(viewIndex)];
    if (v.buffer < 0 || size_t(v.buffer) >= model_.buffers.size())
      fail(where, view + " names no buffer");
    const std::vector<unsigned char>& data = model_.buffers[size_t(v.buffer)].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
      fail(where, view + " lies outside its buffer");
    return {data.data() + v.byteOffset, v.byteLength};
  }

  // The accessor's data becomes `values` (of `componentType`) in a buffer of its own.
  template <typename T>
  void replaceData(tinygltf::Accessor& target, const std::vector<T>& values, int componentType,
                   const std::string& what, const std::string& where) {
    const size_t components =
        size_t(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(target.type)));
    if (components == 0 || values.size() != target.count * components)
      fail(where, "Draco data for " + what + " hold " + std::to_string(values.size()) +
                      " values, the accessor " + std::to_string(target.count) + " elements");
    const size_t bytes = values.size() * sizeof(T);
    budget_ -= std::min<uint64_t>(budget_, bytes);
    tinygltf::Buffer buffer;
    buffer.data.resize(bytes);
    if (bytes > 0) std::memcpy(buffer.data.data(), values.data(), bytes);
    tinygltf::BufferView view;
    view.buffer = static_cast<int>(model_.buffers.size());
    view.byteLength = bytes;
    model_.buffers.push_back(std::move(buffer));
    target.bufferView = static_cast<int>(model_.bufferViews.size());
    model_.bufferViews.push_back(view);
    target.byteOffset = 0;
    target.componentType = componentType;
    target.normalized = false;
    target.sparse.isSparse = false;
  }

  const std::string& path_;
  tinygltf::Model& model_;
  uint64_t budget_;
};

}  // namespace

void decodeDracoPrimitives(const std::string& path, tinygltf::Model& model, uint64_t budgetBytes) {
  DracoPrimitives primitives(path, model, budgetBytes);
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    tinygltf::Mesh& mesh = model.meshes[m];
    const std::string meshWhere =
        mesh.name.empty() ? "mesh " + std::to_string(m) : "mesh '" + mesh.name + "'";
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      primitives.decode(mesh.primitives[p], meshWhere + " primitive " + std::to_string(p));
  }
}

bool stashDracoIndices(nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("meshes") || !doc["meshes"].is_array()) return false;
  bool edited = false;
  for (nlohmann::json& mesh : doc["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    for (nlohmann::json& primitive : mesh["primitives"]) {
      if (!primitive.is_object() || !primitive.contains("indices") ||
          !primitive.contains("extensions") || !primitive["extensions"].is_object())
        continue;
      nlohmann::json& extensions = primitive["extensions"];
      if (!extensions.contains("KHR_draco_mesh_compression") ||
          !extensions["KHR_draco_mesh_compression"].is_object())
        continue;
      extensions["KHR_draco_mesh_compression"][kStashedIndices] = primitive["indices"];
      primitive.erase("indices");
      edited = true;
    }
  }
  return edited;
}

std::vector<unsigned char> glbWithJson(const std::string& path, const std::string& json) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> file((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw Error(path + ": cannot be read");
  // jsonText checked the header and chunk 0 (length, type) before this.
  const auto u32 = [&](size_t at) {
    return uint32_t(file.at(at)) | uint32_t(file.at(at + 1)) << 8 |
           uint32_t(file.at(at + 2)) << 16 | uint32_t(file.at(at + 3)) << 24;
  };
  const size_t rest = std::min(20 + size_t(u32(12)), file.size());  // where the binary chunk starts
  std::string padded = json;
  padded.append((4 - padded.size() % 4) % 4, ' ');
  const size_t total = 20 + padded.size() + (file.size() - rest);
  std::vector<unsigned char> out;
  out.reserve(total);
  for (const char c : {'g', 'l', 'T', 'F'}) out.push_back(static_cast<unsigned char>(c));
  appendU32(out, 2);
  appendU32(out, uint32_t(total));
  appendU32(out, uint32_t(padded.size()));
  for (const char c : {'J', 'S', 'O', 'N'}) out.push_back(static_cast<unsigned char>(c));
  out.insert(out.end(), padded.begin(), padded.end());
  out.insert(out.end(), file.begin() + std::ptrdiff_t(rest), file.end());
  return out;
}

}  // namespace engine::gltf_detail
