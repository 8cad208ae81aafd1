// Private to the glTF loader: EXT_meshopt_compression, decoded with meshoptimizer (Debian's
// libmeshoptimizer-dev). A compressed bufferView names, in its extension, the compressed bytes
// (buffer, byteOffset, byteLength) and how to decode them (count elements of byteStride bytes;
// mode ATTRIBUTES, TRIANGLES or INDICES; filter NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL).
// The buffer the view itself points at is a fallback that a file requiring the extension may
// leave without data. Decoding rewrites the model as if the file had been stored plainly.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace engine::gltf_detail {

// tinygltf reads every buffer's data: a fallback buffer without a URI (all a .gltf may give it,
// and in a .glb anything but buffer 0, the binary chunk) would fail its parse. Gives each such
// buffer one byte of data in a data URI; the views on it are decoded instead of read. Returns
// whether `doc` changed.
bool giveFallbackBuffersData(nlohmann::json& doc, bool binary);

// Decodes every bufferView that carries the extension into a buffer of its own (count x
// byteStride bytes, the view's byteLength) and removes the extension; returns the bytes decoded.
// `budgetBytes` bounds them. Throws Error("<path>: bufferView N: <problem>") for a field missing
// or out of range, a stream meshoptimizer cannot decode, or a decoded size unlike the view's.
uint64_t decodeMeshoptViews(const std::string& path, tinygltf::Model& model, uint64_t budgetBytes);

}  // namespace engine::gltf_detail
