// Checks on a glTF file made before tinygltf parses it, for what tinygltf would crash on, hang on
// or report in misleading words: the JSON's nesting depth (tinygltf's parser recurses once per
// level and overflows the stack at about 16 000), a .glb's container, and required extensions.
// And the file-system callbacks tinygltf reads buffers and images through.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace engine::gltf_detail {

// Deeper JSON than any glTF needs (the schema nests about ten levels; extras may add some).
constexpr size_t kMaxJsonDepth = 256;

// Extensions a file may list as required. Emissive strength scales the emission (scene.h); of
// KHR_materials_specular the factors are read;
// KHR_texture_transform is applied to both textures; KHR_draco_mesh_compression and
// EXT_meshopt_compression are decoded (gltf_draco.h, gltf_meshopt.h).
bool understoodExtension(std::string_view name);

// The JSON text of `path`: the whole file for .gltf, the JSON chunk of a .glb (its header and
// chunk lengths checked). Throws engine::Error("<path>: <problem>").
std::string jsonText(const std::string& path, bool binary);

// What the loader needs to know before tinygltf reads the buffers and images.
struct Preflight {
  // Per glTF image, whether a material uses it as base colour (sRGB-encoded colour: its
  // reduction at decode averages in linear space); empty when `json` does not parse, which
  // tinygltf then reports.
  std::vector<bool> colourImages;
  uint64_t bufferBytes = 0;  // the buffers' declared byteLength, summed
};
// Throws engine::Error("<path>: ...") when `json` nests arrays and objects deeper than
// kMaxJsonDepth; or when it is valid JSON and its extensionsRequired names an extension the
// loader does not understand (before tinygltf, which fails on some of them with unrelated
// words), one of the values tinygltf would silently replace by its default has the wrong shape
// (a negative byteOffset, a 3-value baseColorFactor: the field is named, with its value), or its
// buffers alone exceed kMaxSceneBytes.
Preflight preflight(const std::string& path, const std::string& json);

// tinygltf's file access, restricted: a buffer or image URI must name a regular file (a FIFO
// would block forever, a directory reads as bad_alloc), and paths are used as written (the
// default callbacks expand them through wordexp).
tinygltf::FsCallbacks regularFilesOnly();

}  // namespace engine::gltf_detail
