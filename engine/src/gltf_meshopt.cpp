#include "gltf_meshopt.h"

#include <meshoptimizer.h>

#include <vector>

#include "engine/error.h"

namespace engine::gltf_detail {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

// A non-negative integer field of the extension; `fallback` when absent, -1 when required.
uint64_t field(const tinygltf::Value& ext, const char* name, int64_t fallback,
               const std::string& where) {
  if (!ext.Has(name)) {
    if (fallback < 0) throw Error(where + ": " + kExtension + " needs '" + name + "'");
    return uint64_t(fallback);
  }
  const tinygltf::Value& v = ext.Get(name);
  const double number = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
  if (!(number >= 0.0 && number <= 9.0e15 && number == double(int64_t(number))))
    throw Error(where + ": " + kExtension + " '" + name + "' must be a non-negative integer");
  return uint64_t(number);
}

std::string text(const tinygltf::Value& ext, const char* name, const char* fallback) {
  return ext.Has(name) && ext.Get(name).IsString() ? ext.Get(name).Get<std::string>()
                                                   : std::string(fallback);
}

}  // namespace

bool giveFallbackBuffersData(nlohmann::json& doc, bool binary) {
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return false;
  bool edited = false;
  for (size_t i = 0; i < doc["buffers"].size(); ++i) {
    nlohmann::json& buffer = doc["buffers"][i];
    if (!buffer.is_object() || buffer.contains("uri") || (binary && i == 0)) continue;
    const auto ext = buffer.find("extensions");
    if (ext == buffer.end() || !ext->is_object() || !ext->contains(kExtension)) continue;
    buffer["uri"] = "data:application/octet-stream;base64,AA==";
    buffer["byteLength"] = 1;
    edited = true;
  }
  return edited;
}

uint64_t decodeMeshoptViews(const std::string& path, tinygltf::Model& model, uint64_t budgetBytes) {
  uint64_t decodedBytes = 0;
  for (size_t index = 0; index < model.bufferViews.size(); ++index) {
    tinygltf::BufferView& view = model.bufferViews[index];
    const auto found = view.extensions.find(kExtension);
    if (found == view.extensions.end()) continue;
    const std::string where = path + ": bufferView " + std::to_string(index);
    const tinygltf::Value& ext = found->second;
    if (!ext.IsObject()) throw Error(where + ": " + kExtension + " is not an object");
    const uint64_t source = field(ext, "buffer", -1, where);
    const uint64_t offset = field(ext, "byteOffset", 0, where);
    const uint64_t length = field(ext, "byteLength", -1, where);
    const uint64_t stride = field(ext, "byteStride", -1, where);
    const uint64_t count = field(ext, "count", -1, where);
    const std::string mode = text(ext, "mode", "");
    const std::string filter = text(ext, "filter", "NONE");
    if (source >= model.buffers.size())
      throw Error(where + ": " + kExtension + " buffer " + std::to_string(source) +
                  " does not exist");
    const std::vector<unsigned char>& data = model.buffers[source].data;
    if (offset > data.size() || length > data.size() - offset)
      throw Error(where + ": " + kExtension + " bytes lie outside buffer " +
                  std::to_string(source));
    const bool attributes = mode == "ATTRIBUTES";
    if (!attributes && mode != "TRIANGLES" && mode != "INDICES")
      throw Error(where + ": " + kExtension + " mode '" + mode +
                  "' is not ATTRIBUTES, TRIANGLES or INDICES");
    if (attributes ? stride == 0 || stride % 4 != 0 || stride > 256 : stride != 2 && stride != 4)
      throw Error(where + ": " + kExtension + " byteStride " + std::to_string(stride) +
                  " does not suit mode " + mode);
    if (mode == "TRIANGLES" && count % 3 != 0)
      throw Error(where + ": " + kExtension + " TRIANGLES count " + std::to_string(count) +
                  " is not a multiple of 3");
    const bool filterFits =
        filter == "NONE" ||
        (attributes && ((filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) ||
                        (filter == "QUATERNION" && stride == 8) || filter == "EXPONENTIAL"));
    if (!filterFits)
      throw Error(where + ": " + kExtension + " filter '" + filter + "' does not suit byteStride " +
                  std::to_string(stride) + " and mode " + mode);
    const uint64_t bytes = count * stride;
    if (bytes != view.byteLength)
      throw Error(where + ": " + kExtension + " decodes " + std::to_string(bytes) +
                  " bytes, the view holds " + std::to_string(view.byteLength));
    if (bytes > budgetBytes)
      throw Error(where + ": decoded data exceed the scene byte budget (" +
                  std::to_string(bytes >> 20) + " MB)");
    budgetBytes -= bytes;
    decodedBytes += bytes;

    tinygltf::Buffer decoded;
    decoded.data.resize(size_t(bytes));
    const unsigned char* compressed = data.data() + offset;
    const int status =
        attributes
            ? meshopt_decodeVertexBuffer(decoded.data.data(), count, stride, compressed, length)
        : mode == "TRIANGLES"
            ? meshopt_decodeIndexBuffer(decoded.data.data(), count, stride, compressed, length)
            : meshopt_decodeIndexSequence(decoded.data.data(), count, stride, compressed, length);
    if (status != 0)
      throw Error(where + ": " + kExtension + " data do not decode (meshoptimizer error " +
                  std::to_string(status) + ")");
    if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data.data(), count, stride);
    if (filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data.data(), count, stride);
    if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data.data(), count, stride);

    view.buffer = static_cast<int>(model.buffers.size());
    view.byteOffset = 0;
    view.extensions.erase(found);
    model.buffers.push_back(std::move(decoded));
  }
  return decodedBytes;
}

}  // namespace engine::gltf_detail
