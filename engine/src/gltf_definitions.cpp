// The file's top-level materials, lights and cameras, validated and converted once; nodes then
// instance them (gltf_loader.cpp, gltf_meshes.cpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "gltf_scene_builder.h"

namespace engine::gltf_detail {
namespace {

bool inUnitRange(double v) {
  return v >= 0.0 && v <= 1.0;
}

// A normalTexture read as the textureInfo it extends (its scale is read apart).
tinygltf::TextureInfo asTextureInfo(const tinygltf::NormalTextureInfo& normal) {
  tinygltf::TextureInfo info;
  info.index = normal.index;
  info.texCoord = normal.texCoord;
  info.extensions = normal.extensions;
  return info;
}

}  // namespace

// Maps a glTF texture to the Scene::textures index of its source image.
int SceneBuilder::textureImage(const tinygltf::TextureInfo& info, const std::string& where) const {
  if (info.index < 0) return -1;
  const tinygltf::Texture& texture = at(model_.textures, info.index, "texture", where);
  if (texture.source < 0) {
    fail(where + ": texture " + std::to_string(info.index) +
         " has no source image (image extensions are not supported)");
  }
  at(model_.images, texture.source, "image", where + ": texture " + std::to_string(info.index));
  return texture.source;
}

// KHR_texture_transform on a textureInfo: offset, rotation and scale, finite (its texCoord is
// read by textureCoordinateSet).
TextureTransform SceneBuilder::textureTransform(const tinygltf::TextureInfo& info,
                                                const std::string& where) const {
  TextureTransform t;
  const auto ext = info.extensions.find("KHR_texture_transform");
  if (info.index < 0 || ext == info.extensions.end()) return t;
  const tinygltf::Value& v = ext->second;
  const std::string what = where + " KHR_texture_transform";
  if (!v.IsObject()) fail(what + " must be an object");
  const auto number = [&](const tinygltf::Value& x, const std::string& field) {
    if (!x.IsNumber() || !std::isfinite(x.GetNumberAsDouble()))
      fail(what + " " + field + " must be a finite number");
    return static_cast<float>(x.GetNumberAsDouble());
  };
  const auto pair = [&](const char* field, glm::vec2& out) {
    if (!v.Has(field)) return;
    const tinygltf::Value& a = v.Get(field);
    if (!a.IsArray() || a.ArrayLen() != 2) fail(what + " " + field + " must have 2 values");
    for (int k = 0; k < 2; ++k) out[k] = number(a.Get(k), field);
  };
  pair("offset", t.offset);
  pair("scale", t.scale);
  if (v.Has("rotation")) t.rotation = number(v.Get("rotation"), "rotation");
  return t;
}

// The TEXCOORD_n set a textureInfo samples: KHR_texture_transform's texCoord where it gives one
// (it overrides the textureInfo's), else the textureInfo's; -1 without a texture.
int SceneBuilder::textureCoordinateSet(const tinygltf::TextureInfo& info,
                                       const std::string& where) const {
  if (info.index < 0) return -1;
  if (info.texCoord < 0 || info.texCoord > kMaxTextureCoordinateSet)
    fail(where + " texCoord " + std::to_string(info.texCoord) + " is out of range");
  const auto ext = info.extensions.find("KHR_texture_transform");
  if (ext == info.extensions.end() || !ext->second.IsObject() || !ext->second.Has("texCoord"))
    return info.texCoord;
  const tinygltf::Value& set = ext->second.Get("texCoord");
  const double n = set.IsNumber() ? set.GetNumberAsDouble() : -1.0;
  if (!(n >= 0.0 && n <= kMaxTextureCoordinateSet && n == std::floor(n)))
    fail(where + " KHR_texture_transform texCoord must be an integer in [0, " +
         std::to_string(kMaxTextureCoordinateSet) + "]");
  return static_cast<int>(n);
}

// KHR_materials_specular: its two factors. Its textures (specularTexture, specularColorTexture)
// are not supported; the factors stand for the whole surface.
void SceneBuilder::convertSpecular(const tinygltf::Material& in, const std::string& where,
                                   Material& out) {
  const auto ext = in.extensions.find("KHR_materials_specular");
  if (ext == in.extensions.end()) return;
  const tinygltf::Value& v = ext->second;
  if (!v.IsObject()) fail(where + ": KHR_materials_specular must be an object");
  if (v.Has("specularFactor")) {
    const tinygltf::Value& f = v.Get("specularFactor");
    if (!f.IsNumber() || !inUnitRange(f.GetNumberAsDouble()))
      fail(where + ": KHR_materials_specular specularFactor must be a number in [0, 1]");
    out.specularFactor = static_cast<float>(f.GetNumberAsDouble());
  }
  if (v.Has("specularColorFactor")) {
    const tinygltf::Value& c = v.Get("specularColorFactor");
    if (!c.IsArray() || c.ArrayLen() != 3)
      fail(where + ": KHR_materials_specular specularColorFactor must have 3 values");
    for (int k = 0; k < 3; ++k) {
      const tinygltf::Value& x = c.Get(k);
      if (!x.IsNumber() || !(x.GetNumberAsDouble() >= 0.0) || !std::isfinite(x.GetNumberAsDouble()))
        fail(where + ": KHR_materials_specular specularColorFactor values must be >= 0");
      out.specularColorFactor[k] = static_cast<float>(x.GetNumberAsDouble());
    }
  }
}

// glTF alphaMode: MASK keeps its cutoff (engine/alpha_cutout.h); BLEND is rendered opaque, with
// a warning, because the module's light and the references know no partial coverage.
void SceneBuilder::convertAlphaMode(const tinygltf::Material& in, const std::string& where,
                                    Material& out) {
  if (in.alphaMode == "OPAQUE") return;
  if (in.alphaMode == "BLEND") {
    scene_.warnings.push_back(located(where + " alphaMode BLEND: rendered opaque"));
    return;
  }
  if (in.alphaMode != "MASK")
    fail(where + ": alphaMode must be OPAQUE, MASK or BLEND (got '" + in.alphaMode + "')");
  if (!(in.alphaCutoff >= 0.0) || !std::isfinite(in.alphaCutoff))
    fail(where + ": alphaCutoff must be a finite number >= 0 (got " +
         std::to_string(in.alphaCutoff) + ")");
  out.alphaCutoff = static_cast<float>(in.alphaCutoff);
}

// glTF emission: emissiveFactor (3 values in [0, 1]) times KHR_materials_emissive_strength's
// emissiveStrength (>= 0), and the emissive texture (sRGB, on the material's coordinate set).
void SceneBuilder::convertEmission(const tinygltf::Material& in, const std::string& where,
                                   Material& out) const {
  if (!in.emissiveFactor.empty()) {
    if (in.emissiveFactor.size() != 3) fail(where + ": emissiveFactor must have 3 values");
    for (int c = 0; c < 3; ++c) {
      const double v = in.emissiveFactor[static_cast<size_t>(c)];
      if (!inUnitRange(v)) fail(where + ": emissiveFactor values must lie in [0, 1]");
      out.emissiveFactor[c] = static_cast<float>(v);
    }
  }
  const auto ext = in.extensions.find("KHR_materials_emissive_strength");
  if (ext != in.extensions.end() && ext->second.IsObject() && ext->second.Has("emissiveStrength")) {
    const tinygltf::Value& s = ext->second.Get("emissiveStrength");
    const double strength = s.IsNumber() ? s.GetNumberAsDouble() : -1.0;
    if (!(strength >= 0.0) || !std::isfinite(strength))
      fail(where +
           ": KHR_materials_emissive_strength emissiveStrength must be a finite number "
           ">= 0");
    out.emissiveFactor *= static_cast<float>(strength);
  }
  out.emissiveTexture = textureImage(in.emissiveTexture, where + " emissiveTexture");
  out.emissiveTransform = textureTransform(in.emissiveTexture, where + " emissiveTexture");
}

void SceneBuilder::convertMaterials() {
  for (size_t m = 0; m < model_.materials.size(); ++m) {
    const tinygltf::Material& in = model_.materials[m];
    const tinygltf::PbrMetallicRoughness& pbr = in.pbrMetallicRoughness;
    const std::string where = label("material", in.name, m);
    Material out;
    out.name = in.name;
    if (pbr.baseColorFactor.size() != 4) fail(where + ": baseColorFactor must have 4 values");
    for (int c = 0; c < 4; ++c) {
      const double v = pbr.baseColorFactor[static_cast<size_t>(c)];
      if (!inUnitRange(v)) fail(where + ": baseColorFactor values must lie in [0, 1]");
      out.baseColorFactor[c] = static_cast<float>(v);
    }
    if (!inUnitRange(pbr.metallicFactor)) fail(where + ": metallicFactor must lie in [0, 1]");
    if (!inUnitRange(pbr.roughnessFactor)) fail(where + ": roughnessFactor must lie in [0, 1]");
    out.metallicFactor = static_cast<float>(pbr.metallicFactor);
    out.roughnessFactor = static_cast<float>(pbr.roughnessFactor);
    out.baseColorTexture = textureImage(pbr.baseColorTexture, where + " baseColorTexture");
    out.metallicRoughnessTexture =
        textureImage(pbr.metallicRoughnessTexture, where + " metallicRoughnessTexture");
    out.baseColorTransform = textureTransform(pbr.baseColorTexture, where + " baseColorTexture");
    out.metallicRoughnessTransform =
        textureTransform(pbr.metallicRoughnessTexture, where + " metallicRoughnessTexture");
    const tinygltf::TextureInfo normalInfo = asTextureInfo(in.normalTexture);
    out.normalTexture = textureImage(normalInfo, where + " normalTexture");
    out.normalTransform = textureTransform(normalInfo, where + " normalTexture");
    if (!std::isfinite(in.normalTexture.scale))
      fail(where + ": normalTexture scale must be a finite number");
    out.normalScale = static_cast<float>(in.normalTexture.scale);
    // Vertices carry one texture coordinate set: the one the material's textures sample, the
    // first of base colour (what the bounce takes its colour from), metallic-roughness, normal
    // and emissive texture that exists. A texture on another set is skipped (the factors stand for
    // the surface; without its normal map the surface is smooth; without its emissive texture the
    // material does not glow).
    const int baseSet = textureCoordinateSet(pbr.baseColorTexture, where + " baseColorTexture");
    const int roughSet =
        textureCoordinateSet(pbr.metallicRoughnessTexture, where + " metallicRoughnessTexture");
    const int normalSet = textureCoordinateSet(normalInfo, where + " normalTexture");
    const int emissiveSet = textureCoordinateSet(in.emissiveTexture, where + " emissiveTexture");
    const int set = baseSet >= 0     ? baseSet
                    : roughSet >= 0  ? roughSet
                    : normalSet >= 0 ? normalSet
                                     : std::max(emissiveSet, 0);
    const auto keepOnSet = [&](int sampled, const char* what, int& texture,
                               TextureTransform& transform) {
      if (sampled < 0 || sampled == set) return true;
      scene_.warnings.push_back(located(where + " " + what + ": skipped (it samples TEXCOORD_" +
                                        std::to_string(sampled) +
                                        ", the material's other textures TEXCOORD_" +
                                        std::to_string(set) + "; one set per material is read)"));
      texture = -1;
      transform = TextureTransform{};
      return false;
    };
    keepOnSet(roughSet, "metallicRoughnessTexture", out.metallicRoughnessTexture,
              out.metallicRoughnessTransform);
    keepOnSet(normalSet, "normalTexture", out.normalTexture, out.normalTransform);
    convertEmission(in, where, out);
    // Emission without its texture would glow where the texture is dark: it is left out whole.
    if (!keepOnSet(emissiveSet, "emissiveTexture (and the emission)", out.emissiveTexture,
                   out.emissiveTransform))
      out.emissiveFactor = glm::vec3(0.0f);
    materialCoordinateSets_.push_back(set);
    out.doubleSided = in.doubleSided;
    convertAlphaMode(in, where, out);
    convertSpecular(in, where, out);
    scene_.materials.push_back(std::move(out));
  }
}

void SceneBuilder::convertLights() {
  for (size_t l = 0; l < model_.lights.size(); ++l) {
    const tinygltf::Light& in = model_.lights[l];
    const std::string where = label("light", in.name, l);
    Light out;
    out.name = in.name;
    if (in.type == "directional") {
      out.type = LightType::Directional;
    } else if (in.type == "point") {
      out.type = LightType::Point;
    } else if (in.type == "spot") {
      out.type = LightType::Spot;
    } else {
      fail(where + ": unknown light type '" + in.type + "'");
    }
    if (!in.color.empty()) {
      if (in.color.size() != 3) fail(where + ": color must have 3 values");
      for (int c = 0; c < 3; ++c) {
        const double v = in.color[static_cast<size_t>(c)];
        if (!(v >= 0.0) || !std::isfinite(v)) fail(where + ": color values must be >= 0");
        out.color[c] = static_cast<float>(v);
      }
    }
    if (!(in.intensity >= 0.0) || !std::isfinite(in.intensity)) {
      fail(where + ": intensity must be >= 0");
    }
    if (!(in.range >= 0.0) || !std::isfinite(in.range)) fail(where + ": range must be >= 0");
    out.intensity = static_cast<float>(in.intensity);
    out.range = static_cast<float>(in.range);
    if (out.type == LightType::Spot) {
      const double inner = in.spot.innerConeAngle;
      const double outer = in.spot.outerConeAngle;
      if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2)) {
        fail(where +
             ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= "
             "pi/2 (got innerConeAngle " +
             std::to_string(inner) + ", outerConeAngle " + std::to_string(outer) + ")");
      }
      out.innerConeAngle = static_cast<float>(inner);
      out.outerConeAngle = static_cast<float>(outer);
    }
    lights_.push_back(std::move(out));
  }
}

void SceneBuilder::convertCameras() {
  for (size_t c = 0; c < model_.cameras.size(); ++c) {
    const tinygltf::Camera& in = model_.cameras[c];
    const std::string where = label("camera", in.name, c);
    Camera out;
    out.name = in.name;
    if (in.type == "perspective") {
      const tinygltf::PerspectiveCamera& p = in.perspective;
      if (!(p.yfov > 0.0 && p.yfov < std::numbers::pi)) fail(where + ": yfov must be in (0, pi)");
      if (!(p.znear > 0.0) || !std::isfinite(p.znear)) fail(where + ": znear must be > 0");
      if (!(p.zfar == 0.0 || p.zfar > p.znear) || !std::isfinite(p.zfar)) {
        fail(where + ": zfar must be > znear (or absent for an infinite projection)");
      }
      if (!(p.aspectRatio >= 0.0) || !std::isfinite(p.aspectRatio)) {
        fail(where + ": aspectRatio must be > 0");
      }
      out.perspective = true;
      out.yfov = static_cast<float>(p.yfov);
      out.aspectRatio = static_cast<float>(p.aspectRatio);
      out.znear = static_cast<float>(p.znear);
      out.zfar = static_cast<float>(p.zfar);
    } else if (in.type == "orthographic") {
      const tinygltf::OrthographicCamera& o = in.orthographic;
      if (!(o.xmag != 0.0 && o.ymag != 0.0) || !std::isfinite(o.xmag) || !std::isfinite(o.ymag)) {
        fail(where + ": xmag and ymag must be non-zero");
      }
      if (!(o.znear >= 0.0) || !(o.zfar > o.znear) || !std::isfinite(o.zfar)) {
        fail(where + ": orthographic znear must be >= 0 and zfar > znear");
      }
      out.perspective = false;
      out.xmag = static_cast<float>(std::abs(o.xmag));
      out.ymag = static_cast<float>(std::abs(o.ymag));
      out.znear = static_cast<float>(o.znear);
      out.zfar = static_cast<float>(o.zfar);
    } else {
      fail(where + ": unknown camera type '" + in.type + "'");
    }
    cameras_.push_back(std::move(out));
  }
}

}  // namespace engine::gltf_detail
