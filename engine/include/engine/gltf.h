// glTF 2.0 in and out of engine::Scene.
//
// Loading flattens the default scene (else scene 0, else every root node) into one world-space
// triangle list: positions go through each node's world matrix, normals through its
// inverse-transpose, and mirrored nodes (negative determinant) get their winding flipped so
// counter-clockwise stays front-facing. Supported: triangle lists, strips and fans (indexed or
// not, u8/u16/u32 indices); POSITION, NORMAL, TEXCOORD_0 (float, or normalized u8/u16 UVs);
// pbrMetallicRoughness factors and textures; KHR_materials_specular's factors (not its
// textures); KHR_texture_transform; KHR_lights_punctual; perspective and orthographic cameras.
// Points and lines primitives and optional extensions it does not read are skipped with one
// line each in Scene::warnings. Ignored on purpose: samplers (repeat wrap and trilinear filtering
// are assumed), emission, normal/occlusion maps, alpha modes, skins, morph targets and animations.
// Primitives without a material get an appended default material: opaque white, metallic 0,
// roughness 0.5, single-sided. What is read, skipped and refused: docs/gltf.md.
#pragma once

#include <cstdint>
#include <string>

#include "engine/scene.h"

namespace engine {

// What one scene's buffers and decoded textures may hold together: a file past it is refused
// with its size (before its buffers are read, when they alone exceed it), not left to run the
// machine out of memory. Textures count at their decoded size (engine::TextureSize).
constexpr uint64_t kMaxSceneBytes = uint64_t{2} << 30;

// Loads a .gltf or .glb (chosen by extension). Images are decoded through OpenImageIO into
// Scene::textures, indexed like the glTF images. A scene without triangles or without lights is
// an error. Throws engine::Error("<path>: <problem>") on any failure, never crashes on bad input.
Scene loadGltf(const std::string& path);

// Writes one self-contained .gltf (buffer embedded as a base64 data URI). Each texture i goes to
// "<stem>_tex<i>.png" beside it, referenced by a relative URI. Consecutive triangles sharing a
// material become one primitive, so loadGltf() returns the triangles in the same order. The .gltf
// is written to "<path>.tmp-<pid>" and renamed over <path>, so a failure never leaves a partial
// file. Throws engine::Error("<path>: <problem>").
void writeGltf(const Scene& scene, const std::string& path);

}  // namespace engine
