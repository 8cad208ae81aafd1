// Private to the glTF loader: KHR_draco_mesh_compression, decoded with Google's Draco library
// (Debian's libdraco-dev, behind engine/draco/draco_decoder.h). A compressed primitive keeps its
// accessors (count, type, bounds) but stores their data as one Draco bitstream in a bufferView;
// the extension maps each attribute name to the bitstream's attribute id. Decoding rewrites the
// model as if the file had been stored plainly, so everything after it reads ordinary accessors.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace engine::gltf_detail {

// tinygltf (built without Draco) refuses a primitive whose index accessor has no bufferView,
// which is how compressed primitives come. Before it parses, each compressed primitive's
// "indices" moves into its extension object (as "vsgl:indices"); decodeDracoPrimitives moves it
// back. Returns whether `doc` changed.
bool stashDracoIndices(nlohmann::json& doc);

// The bytes of the .glb at `path` with its JSON chunk replaced by `json` (its binary chunk as it
// is), for tinygltf to parse from memory (after the edits here and in gltf_meshopt.h). Throws
// Error("<path>: ...") when the file cannot be read.
std::vector<unsigned char> glbWithJson(const std::string& path, const std::string& json);

// Decodes every primitive that carries the extension: its indices become unsigned 32-bit and
// each compressed attribute float (normalized integers mapped to [0, 1] or [-1, 1] as glTF
// 3.11 reads them), each in a buffer appended to `model`, and the extension is removed from the
// primitive. `budgetBytes` bounds the decoded data. Throws Error("<path>: mesh 'm' primitive p:
// <problem>") for a bitstream that does not decode, an attribute id it lacks, or a count that
// differs from the accessor's.
void decodeDracoPrimitives(const std::string& path, tinygltf::Model& model, uint64_t budgetBytes);

}  // namespace engine::gltf_detail
