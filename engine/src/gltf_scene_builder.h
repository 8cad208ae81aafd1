// Private to the glTF loader: the conversion of a parsed tinygltf model into an engine::Scene. Its
// member functions live by concern: gltf_loader.cpp (build, node traversal, camera and light
// instances), gltf_definitions.cpp (materials, lights, cameras), gltf_meshes.cpp (mesh baking).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene.h"
#include "gltf_accessors.h"

namespace engine::gltf_detail {

// Unit vector, or nullopt when v is zero or not finite.
inline std::optional<glm::dvec3> tryNormalize(const glm::dvec3& v) {
  const double length = glm::length(v);
  if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
  return v / length;
}

// Converts the tinygltf model into a Scene; every problem becomes Error("<path>: <problem>").
class SceneBuilder : private ModelReader {
 public:
  SceneBuilder(const std::string& path, const tinygltf::Model& model, Scene& scene)
      : ModelReader(path, model), scene_(scene) {}

  void build();

 private:
  static std::string label(const std::string& kind, const std::string& name, size_t index) {
    return name.empty() ? kind + " " + std::to_string(index) : kind + " '" + name + "'";
  }

  // gltf_definitions.cpp
  int textureImage(const tinygltf::TextureInfo& info, const std::string& where) const;
  TextureTransform textureTransform(const tinygltf::TextureInfo& info,
                                    const std::string& where) const;
  int textureCoordinateSet(const tinygltf::TextureInfo& info, const std::string& where) const;
  void convertMaterials();
  void convertSpecular(const tinygltf::Material& in, const std::string& where, Material& out);
  void convertEmission(const tinygltf::Material& in, const std::string& where, Material& out) const;
  void convertAlphaMode(const tinygltf::Material& in, const std::string& where, Material& out);
  void convertLights();
  void convertCameras();

  // gltf_loader.cpp
  glm::dmat4 localMatrix(const tinygltf::Node& node, const std::string& where) const;
  std::vector<int> rootNodes() const;
  void traverseNodes();
  void addCamera(int cameraIndex, const glm::dmat4& world, const std::string& where);
  void addLight(const tinygltf::Node& node, const glm::dmat4& world, const std::string& where);

  // gltf_meshes.cpp
  uint32_t materialFor(const tinygltf::Primitive& primitive, const std::string& where);
  void addMesh(int meshIndex, const glm::dmat4& world, const std::string& nodeWhere);
  void addPrimitive(const tinygltf::Primitive& primitive, const glm::dmat4& world,
                    const std::string& where);

  Scene& scene_;
  std::vector<Light> lights_;    // model.lights, validated; instanced by nodes
  std::vector<Camera> cameras_;  // model.cameras, validated; instanced by nodes
  std::optional<Material> defaultMaterial_;
  // Per glTF material, the TEXCOORD_n set its textures sample (0 without textures); the default
  // material has none.
  std::vector<int> materialCoordinateSets_;
  // glTF sets no limit; a set past this is a broken file, not a real one.
  static constexpr int kMaxTextureCoordinateSet = 31;
};

}  // namespace engine::gltf_detail
