#include "gltf_preflight.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <system_error>

#include "engine/error.h"
#include "engine/gltf.h"

namespace engine::gltf_detail {
namespace {

constexpr std::string_view kUnderstoodExtensions[] = {
    "EXT_meshopt_compression",         "KHR_draco_mesh_compression", "KHR_lights_punctual",
    "KHR_materials_emissive_strength", "KHR_materials_specular",     "KHR_texture_transform"};

bool isRegularFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::string whatItIs(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status s = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(s)) return "does not exist";
  if (std::filesystem::is_directory(s)) return "is a directory";
  return "is not a regular file";
}

bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void*) {
  if (!isRegularFile(path)) {
    if (err) *err += "'" + path + "' " + whatItIs(path) + "\n";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) {
    if (err) *err += "'" + path + "' cannot be read\n";
    return false;
  }
  return true;
}

// tinygltf replaces a value of the wrong shape by its default without a word (a 3-value
// baseColorFactor becomes white, a negative byteOffset 0). These are the values the loader uses
// whose shape tinygltf does not check: a count of `size` numbers (0: any count), or a
// non-negative integer.
struct Shape {
  const char* array;   // top-level array
  const char* object;  // sub-object of each element, or nullptr
  const char* field;
  size_t size;  // numbers in an array; 0: a non-negative integer
};
constexpr Shape kShapes[] = {
    {"accessors", nullptr, "byteOffset", 0},
    {"accessors", nullptr, "count", 0},
    {"bufferViews", nullptr, "byteOffset", 0},
    {"bufferViews", nullptr, "byteLength", 0},
    {"bufferViews", nullptr, "byteStride", 0},
    {"buffers", nullptr, "byteLength", 0},
    {"materials", "pbrMetallicRoughness", "baseColorFactor", 4},
    {"nodes", nullptr, "matrix", 16},
    {"nodes", nullptr, "translation", 3},
    {"nodes", nullptr, "rotation", 4},
    {"nodes", nullptr, "scale", 3},
};

void checkShapes(const std::string& path, const nlohmann::json& doc) {
  for (const Shape& shape : kShapes) {
    const auto items = doc.find(shape.array);
    if (items == doc.end() || !items->is_array()) continue;
    for (size_t i = 0; i < items->size(); ++i) {
      const nlohmann::json* holder = &(*items)[i];
      std::string where = std::string(shape.array) + "[" + std::to_string(i) + "].";
      if (shape.object) {
        const auto sub = holder->find(shape.object);
        if (!holder->is_object() || sub == holder->end()) continue;
        holder = &*sub;
        where += std::string(shape.object) + ".";
      }
      if (!holder->is_object()) continue;
      const auto value = holder->find(shape.field);
      if (value == holder->end()) continue;
      where += shape.field;
      if (shape.size == 0) {
        if (!value->is_number_unsigned())
          throw Error(path + ": " + where + " must be a non-negative integer, got " +
                      value->dump());
      } else if (!value->is_array() || value->size() != shape.size ||
                 !std::all_of(value->begin(), value->end(),
                              [](const nlohmann::json& x) { return x.is_number(); })) {
        throw Error(path + ": " + where + " must be " + std::to_string(shape.size) +
                    " numbers, got " + value->dump());
      }
    }
  }
}

uint32_t readU32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);  // glTF's binary container is little-endian, as x86
  return v;
}

}  // namespace

bool understoodExtension(std::string_view name) {
  return std::find(std::begin(kUnderstoodExtensions), std::end(kUnderstoodExtensions), name) !=
         std::end(kUnderstoodExtensions);
}

std::string jsonText(const std::string& path, bool binary) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot be read");
  if (!binary) {
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.empty()) throw Error(path + ": file is empty");
    return text;
  }
  // Header: magic "glTF", version 2, total length; then chunk 0: length, type "JSON", data. Only
  // these are read here, not the binary chunk tinygltf reads next.
  std::string header(20, '\0');
  in.read(header.data(), 20);
  if (in.gcount() == 0) throw Error(path + ": file is empty");
  if (in.gcount() < 20 || header.compare(0, 4, "glTF") != 0)
    throw Error(path + ": not a binary glTF (no 'glTF' header)");
  if (readU32(header, 4) != 2) throw Error(path + ": binary glTF version is not 2");
  if (header.compare(16, 4, "JSON") != 0) throw Error(path + ": first chunk is not JSON");
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  const uint32_t length = readU32(header, 12);  // chunk 0's length
  if (ec || length > size - 20) throw Error(path + ": JSON chunk runs past the end of the file");
  std::string json(length, '\0');
  in.read(json.data(), length);
  if (uint64_t(in.gcount()) != length) throw Error(path + ": JSON chunk cannot be read");
  return json;
}

Preflight preflight(const std::string& path, const std::string& json) {
  // Depth outside strings, escapes skipped: a scan, not a parse, so it cannot overflow itself.
  size_t depth = 0;
  bool inString = false;
  for (size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw Error(path + ": JSON nests deeper than " + std::to_string(kMaxJsonDepth) +
                    " levels (at byte " + std::to_string(i) + ")");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  const nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return {};  // tinygltf words the syntax error
  checkShapes(path, doc);
  Preflight out;
  for (const nlohmann::json& b : doc.value("buffers", nlohmann::json::array()))
    if (b.is_object() && b.contains("byteLength") && b["byteLength"].is_number_unsigned())
      out.bufferBytes += b["byteLength"].get<uint64_t>();
  if (out.bufferBytes > kMaxSceneBytes)
    throw Error(path + ": its buffers hold " + std::to_string(out.bufferBytes >> 20) +
                " MB, more than the " + std::to_string(kMaxSceneBytes >> 20) +
                " MB a scene may use (engine::kMaxSceneBytes)");
  const auto required = doc.find("extensionsRequired");
  if (required != doc.end() && required->is_array())
    for (const nlohmann::json& name : *required)
      if (name.is_string() && !understoodExtension(name.get<std::string>()))
        throw Error(path + ": requires unsupported extension '" + name.get<std::string>() + "'");
  // Colour (sRGB) images: base colour and emission, through materials[].pbrMetallicRoughness.
  // baseColorTexture.index or materials[].emissiveTexture.index and textures[].source;
  // references out of range are left to the scene builder to report.
  const nlohmann::json images = doc.value("images", nlohmann::json::array());
  const nlohmann::json textures = doc.value("textures", nlohmann::json::array());
  std::vector<bool>& colour = out.colourImages;
  colour.assign(images.is_array() ? images.size() : 0, false);
  const auto markColour = [&](const nlohmann::json& m, std::initializer_list<const char*> keys) {
    const nlohmann::json* t = &m;
    for (const char* key : keys) {
      if (!t->is_object() || !t->contains(key)) return;
      t = &(*t)[key];
    }
    if (!t->is_number_unsigned() || !textures.is_array() || *t >= textures.size()) return;
    const nlohmann::json& texture = textures[t->get<size_t>()];
    if (!texture.is_object() || !texture.contains("source")) return;
    const nlohmann::json& source = texture["source"];
    if (source.is_number_unsigned() && source.get<size_t>() < colour.size())
      colour[source.get<size_t>()] = true;
  };
  for (const nlohmann::json& m : doc.value("materials", nlohmann::json::array())) {
    markColour(m, {"pbrMetallicRoughness", "baseColorTexture", "index"});
    markColour(m, {"emissiveTexture", "index"});
  }
  return out;
}

tinygltf::FsCallbacks regularFilesOnly() {
  tinygltf::FsCallbacks fs{};
  // Anything that exists "exists", so that ReadWholeFile can say what it is instead.
  fs.FileExists = [](const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
  };
  fs.ExpandFilePath = [](const std::string& path, void*) { return path; };
  fs.ReadWholeFile = &readRegularFile;
  fs.WriteWholeFile = nullptr;  // the loader writes nothing
  fs.user_data = nullptr;
  return fs;
}

}  // namespace engine::gltf_detail
