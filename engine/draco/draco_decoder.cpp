#include "draco_decoder.h"

#include <draco/compression/decode.h>

#include <algorithm>
#include <memory>

namespace engine::draco_decoder {

std::string decode(std::span<const uint8_t> bitstream,
                   std::span<const std::pair<int, int>> attributes, uint64_t budgetBytes,
                   Mesh& out) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bitstream.data()), bitstream.size());
  draco::Decoder decoder;
  draco::StatusOr<std::unique_ptr<draco::Mesh>> decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    return "Draco data does not decode (" + decoded.status().error_msg_string() + ")";
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) return "Draco data does not decode to a mesh";

  uint64_t bytes = uint64_t{mesh->num_faces()} * 3 * sizeof(uint32_t);
  for (const auto& [id, components] : attributes)
    bytes += uint64_t{mesh->num_points()} * uint64_t(std::max(components, 0)) * sizeof(float);
  if (bytes > budgetBytes)
    return "decoded Draco data (" + std::to_string(bytes >> 20) +
           " MB) exceed the scene byte budget";

  out.points = mesh->num_points();
  out.corners.clear();
  out.corners.reserve(size_t{mesh->num_faces()} * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.corners.push_back(mesh->face(f)[k].value());
  out.attributes.clear();
  for (const auto& [id, components] : attributes) {
    const draco::PointAttribute* source = mesh->GetAttributeByUniqueId(uint32_t(id));
    if (id < 0 || source == nullptr)
      return "attribute id " + std::to_string(id) + " is not in the Draco bitstream";
    if (components < 1 || components > source->num_components())
      return "attribute id " + std::to_string(id) + " holds " +
             std::to_string(source->num_components()) + " components, not " +
             std::to_string(components);
    Attribute& attribute = out.attributes.emplace_back();
    attribute.id = id;
    attribute.components = components;
    attribute.values.resize(size_t{mesh->num_points()} * size_t(components));
    for (draco::PointIndex p(0); p < mesh->num_points(); ++p)
      if (!source->ConvertValue<float>(source->mapped_index(p), int8_t(components),
                                       &attribute.values[size_t{p.value()} * size_t(components)]))
        return "attribute id " + std::to_string(id) + " cannot be read as floats";
  }
  return {};
}

}  // namespace engine::draco_decoder
