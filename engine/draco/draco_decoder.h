// Draco mesh decoding behind a wall of its own. Debian 12's libdraco (1.5.5, built with its glTF
// transcoder) carries a second copy of tinygltf: linked into the engine directly, its tinygltf
// functions replace libtinygltf's, whose Model they do not match, and every glTF load corrupts
// the heap. So the decoder is a shared library of its own (vsgl_draco_decoder) that links
// libdraco statically, hides every symbol of it (-fvisibility=hidden, --exclude-libs) and exports
// only the function below, whose interface holds no Draco or tinygltf type.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#if defined(VSGL_DRACO_DECODER_BUILD)
#define VSGL_DRACO_EXPORT __attribute__((visibility("default")))
#else
#define VSGL_DRACO_EXPORT
#endif

namespace engine::draco_decoder {

struct Attribute {
  int id = -1;                // the bitstream's unique attribute id
  int components = 0;         // as requested
  std::vector<float> values;  // points x components; normalized integers in [0, 1] or [-1, 1]
};

struct Mesh {
  uint32_t points = 0;
  std::vector<uint32_t> corners;      // 3 per triangle, point indices
  std::vector<Attribute> attributes;  // in the order requested
};

// Decodes a Draco mesh bitstream and reads each requested attribute (unique id, component count)
// as floats. Returns an empty string on success, else the problem in words (the bitstream does
// not decode, an id it lacks, more components than it holds, a decoded size above budgetBytes).
VSGL_DRACO_EXPORT std::string decode(std::span<const uint8_t> bitstream,
                                     std::span<const std::pair<int, int>> attributes,
                                     uint64_t budgetBytes, Mesh& out);

}  // namespace engine::draco_decoder
