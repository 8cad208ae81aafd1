// A scene flattened for compute rendering: every mesh instance is baked into one world-space
// triangle list, so rasterizer passes index one vertex buffer and one index buffer.
// Conventions (docs/architecture.md): glTF's right-handed, +Y up, metres; radiometric light
// units taken numerically from KHR_lights_punctual (intensity -> W/sr, illuminance -> W/m^2).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace engine {

// Decoded texture, always 8-bit RGBA. Whether the bytes are sRGB-encoded depends on the role
// the material gives it (base colour: sRGB; metallic-roughness: linear), not on the image.
struct Texture {
  std::string name;  // file name or "<gltf>#image<i>" for embedded images; used in errors
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba8;  // width * height * 4 bytes, rows top to bottom
};

// Largest side of the GPU's packed texture layers (engine::uploadScene downsamples bigger
// textures to it). The glTF loader reduces larger textures towards it as it decodes them
// (engine::TextureSize).
constexpr int kMaxTextureSize = 1024;

// KHR_texture_transform of one texture: texture coordinates (u, v) become
// offset + R(rotation) (scale * (u, v)), R turning the coordinates counter-clockwise by
// `rotation` radians as the extension defines it (u' = cos u + sin v, v' = -sin u + cos v for a
// unit scale), which turns the image clockwise. Identity by default.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};

  bool identity() const {
    return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
  }
  // Rows of the 2 x 3 affine map of (u, v, 1), in double (the CPU references) and as the GPU
  // stores them (gpu::SceneMaterial).
  glm::dvec3 rowU() const;
  glm::dvec3 rowV() const;
};

// glTF 2.0 metallic-roughness material. Emission is ignored (documented in architecture.md):
// one-bounce transport from emissive surfaces is outside this module's scope.
struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};      // linear RGBA
  float metallicFactor = 1.0f;          // [0, 1]
  float roughnessFactor = 1.0f;         // perceptual roughness r in [0, 1]; GGX alpha = r^2
  int baseColorTexture = -1;            // index into Scene::textures, -1 = none
  int metallicRoughnessTexture = -1;    // glTF packing: roughness in G, metallic in B
  TextureTransform baseColorTransform;  // KHR_texture_transform of each texture
  TextureTransform metallicRoughnessTransform;
  // Tangent-space normal map (glTF normalTexture): RGB = (x, y, z) * 0.5 + 0.5, x and y scaled by
  // normalScale. The tangent frame is the triangle's own, from its texture coordinates (the
  // file's TANGENT attribute is not read): engine/gbuffer_reference.h, perturbedNormal.
  int normalTexture = -1;
  float normalScale = 1.0f;
  TextureTransform normalTransform;
  // Emitted radiance (glTF emissive: factor x texture, the factor times
  // KHR_materials_emissive_strength), W sr^-1 m^-2. It is added to the frame by the host's
  // direct light and does not bounce (the RSM's flux carries reflected light only).
  glm::vec3 emissiveFactor{0.0f};
  int emissiveTexture = -1;  // sRGB, like the base colour
  TextureTransform emissiveTransform;
  // KHR_materials_specular: a dielectric's specular reflection, F0 = min(0.04 x colour, 1) x
  // strength and F90 = strength (Schlick); metals keep F0 = base colour and F90 = 1. Strength 0
  // makes the dielectric purely diffuse. Its textures are not supported (the factors are used).
  float specularFactor = 1.0f;          // [0, 1]
  glm::vec3 specularColorFactor{1.0f};  // linear RGB, >= 0
  bool doubleSided = false;
  // glTF alphaMode MASK: where the alpha (baseColorFactor.a x the base colour texture's alpha)
  // lies below the cutoff there is no surface, for the light as for the camera
  // (engine/alpha_cutout.h). 0 for OPAQUE and BLEND (rendered opaque), and for a MASK cutoff of
  // 0, which keeps every texel alike.
  float alphaCutoff = 0.0f;
};

enum class LightType : uint32_t { Directional = 0, Point = 1, Spot = 2 };

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};                // world space (unused for directional)
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit, the way light travels (node -Z), world space
  glm::vec3 color{1.0f};                   // linear RGB, multiplies intensity
  float intensity = 1.0f;                  // point/spot: W/sr; directional: W/m^2 on a normal plane
  float range = 0.0f;                      // metres; 0 = infinite (KHR_lights_punctual)
  float innerConeAngle = 0.0f;             // radians, spot only, in [0, outer)
  float outerConeAngle = 0.7853982f;       // radians, spot only, in (0, pi/2]
  bool operator==(const Light&) const = default;
};

// KHR_lights_punctual's spot falloff as scale and offset: falloff(cos) = saturate(cos * x + y)^2,
// 1 inside the inner cone, 0 outside the outer cone.
glm::vec2 spotFalloff(const Light& light);

struct Camera {
  std::string name;
  glm::mat4 cameraToWorld{1.0f};  // camera looks down its local -Z, +Y up (glTF)
  bool perspective = true;
  float yfov = 0.8f;         // radians, perspective
  float aspectRatio = 0.0f;  // width / height; 0 = take it from the viewport
  float znear = 0.05f;       // metres, > 0
  float zfar = 0.0f;         // metres; 0 = infinite (perspective only)
  float xmag = 1.0f;         // orthographic half width, metres
  float ymag = 1.0f;         // orthographic half height, metres
};

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
};

struct Scene {
  std::string source;  // file the scene came from, or "builtin:<name>"

  // One entry per vertex, world space. Normals are unit length; when a glTF mesh has none they
  // are generated as area-weighted averages of the face normals sharing a vertex position.
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;     // the set the material samples (TEXCOORD_n); (0,0) without it
  std::vector<uint32_t> indices;  // 3 per triangle, counter-clockwise front faces
  std::vector<uint32_t> triangleMaterial;  // one material index per triangle

  std::vector<Material> materials;  // never empty: loaders add a default material when needed
  std::vector<Texture> textures;
  std::vector<Light> lights;
  std::vector<Camera> cameras;  // may be empty: see defaultCamera()
  // What the loader read past without using, one line each ("<file>: <what was skipped>"): a
  // points or lines primitive, an optional extension it does not read. The programs print
  // them; nothing else reads them.
  std::vector<std::string> warnings;

  uint32_t triangleCount() const { return static_cast<uint32_t>(indices.size() / 3); }
  Bounds bounds() const;
};

// A perspective camera that frames the whole scene from its +Z side, used when the glTF has none.
Camera defaultCamera(const Scene& scene);

// A camera's frame as the glTF loader keeps it (a scaled or skewed node would skew the view): a
// frame that is already rigid to float precision (unit axes, orthogonal within 1e-6, right-handed)
// as its floats, so that a camera written to a file reads back bit for bit; any other with the
// viewing axis Z normalised, Y made orthogonal to it and X = Y x Z, in double and rounded once.
// Empty when Z or Y is degenerate.
std::optional<glm::mat4> rigidCameraFrame(const glm::mat4& world);

// A light's direction as files carry it: a vector of unit length to float precision
// (|length - 1| <= 1e-6) is kept as its floats, any other is normalised in double; empty when
// it is zero or not finite. The glTF writer stores a light's direction through it as the node's
// -Z and the loader reads the node's -Z back through it, so a light written and read back keeps
// its direction bit for bit.
std::optional<glm::vec3> fileLightDirection(const glm::vec3& direction);

}  // namespace engine
