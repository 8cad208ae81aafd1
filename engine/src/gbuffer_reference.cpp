#include "engine/gbuffer_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <string>

#include "engine/error.h"
#include "shared/raster.h"

namespace engine {
namespace {

// Barycentrics (u, v) of the ray's hit with the plane of (a, b, c), as planeBarycentrics().
glm::dvec2 planeBarycentrics(const CameraRay& ray, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  glm::dvec3 e1 = b - a, e2 = c - a;
  glm::dvec3 p = glm::cross(ray.dir, e2);
  double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-30) return glm::dvec2(1.0 / 3.0);
  glm::dvec3 s = ray.origin - a;
  glm::dvec3 q = glm::cross(s, e1);
  return glm::dvec2(glm::dot(s, p), glm::dot(ray.dir, q)) / det;
}

// A texel of an 8-bit RGBA texture in linear space; sRGB decoding applies to RGB only.
glm::dvec4 texel(const Texture& t, int64_t x, int64_t y, bool srgb) {
  auto wrap = [](int64_t i, int n) { return static_cast<size_t>(((i % n) + n) % n); };
  const uint8_t* rgba =
      &t.rgba8[(wrap(y, t.height) * static_cast<size_t>(t.width) + wrap(x, t.width)) * 4];
  glm::dvec4 c;
  for (int k = 0; k < 4; ++k) {
    double v = rgba[k] / 255.0;
    c[k] = (srgb && k < 3) ? srgbToLinear(v) : v;
  }
  return c;
}

// Bilinear filtering with repeat addressing, Vulkan's texel-centre convention (u * size - 0.5).
glm::dvec4 sampleBilinear(const Texture& t, glm::dvec2 uv, bool srgb) {
  double x = uv.x * t.width - 0.5, y = uv.y * t.height - 0.5;
  double x0 = std::floor(x), y0 = std::floor(y);
  double fx = x - x0, fy = y - y0;
  auto ix = static_cast<int64_t>(x0), iy = static_cast<int64_t>(y0);
  glm::dvec4 top = glm::mix(texel(t, ix, iy, srgb), texel(t, ix + 1, iy, srgb), fx);
  glm::dvec4 bottom = glm::mix(texel(t, ix, iy + 1, srgb), texel(t, ix + 1, iy + 1, srgb), fx);
  return glm::mix(top, bottom, fy);
}

GBufferSample resolvePixel(const Scene& scene, const View& view, uint32_t x, uint32_t y,
                           uint64_t vis, BackFaces backFaces) {
  if (static_cast<uint32_t>(vis >> 32) == RASTER_EMPTY_HI) return {};
  const auto tri = static_cast<uint32_t>(vis & 0xFFFFFFFFu);
  glm::dvec3 pos[3];
  for (int k = 0; k < 3; ++k) pos[k] = scene.positions[scene.indices[3 * size_t{tri} + k]];
  const CameraRay ray = cameraRayReference(view, glm::dvec2(x + 0.5, y + 0.5));
  GBufferSample s =
      surfaceAt(scene, tri, planeBarycentrics(ray, pos[0], pos[1], pos[2]), ray.dir, backFaces);
  s.depth = std::bit_cast<float>(static_cast<uint32_t>(vis >> 32));
  return s;
}

// Octahedral decode (shaders/common/octahedral.glsl) in double.
glm::dvec3 octDecode(glm::dvec2 e) {
  glm::dvec3 n(e, 1.0 - std::abs(e.x) - std::abs(e.y));
  if (n.z < 0.0) {
    glm::dvec2 sign(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    n = glm::dvec3((1.0 - std::abs(n.y)) * sign.x, (1.0 - std::abs(n.x)) * sign.y, n.z);
  }
  return glm::normalize(n);
}

template <class T>
T loadTexel(std::span<const std::byte> bytes, size_t index) {
  T value;
  std::memcpy(&value, bytes.data() + index * sizeof(T), sizeof(T));
  return value;
}

// Vulkan's SNORM decode: the most negative code also maps to -1.
double decodeSnorm16(int16_t v) {
  return std::max(v / 32767.0, -1.0);
}

glm::dvec4 halfsToDouble(std::span<const std::byte> bytes, size_t pixel) {
  glm::dvec4 r;
  for (int k = 0; k < 4; ++k)
    r[k] = glm::unpackHalf1x16(loadTexel<uint16_t>(bytes, pixel * 4 + static_cast<size_t>(k)));
  return r;
}

}  // namespace

CameraRay cameraRayReference(const View& view, glm::dvec2 pixel) {
  // camera_ray.glsl in double, with the same float matrix as the shader.
  const glm::dmat4 invViewProj(view.invViewProj);
  const glm::dvec2 ndc = pixel / glm::dvec2(view.width, view.height) * 2.0 - 1.0;
  auto unproject = [&](double z) {
    const glm::dvec4 h = invViewProj * glm::dvec4(ndc, z, 1.0);
    return glm::dvec3(h) / h.w;
  };
  const glm::dvec3 origin = unproject(0.0);
  return {origin, glm::normalize(unproject(0.5) - origin)};
}

glm::dvec3 perturbedNormal(glm::dvec3 normal, const glm::dvec3 corners[3], const glm::dvec2 uvs[3],
                           glm::dvec3 mapped) {
  const glm::dvec3 e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
  const glm::dvec2 d1 = uvs[1] - uvs[0], d2 = uvs[2] - uvs[0];
  const double det = d1.x * d2.y - d2.x * d1.y;
  if (!(std::abs(det) > 0.0)) return normal;
  const glm::dvec3 dpdu = (e1 * d2.y - e2 * d1.y) / det, dpdv = (e2 * d1.x - e1 * d2.x) / det;
  const glm::dvec3 t = dpdu - normal * glm::dot(normal, dpdu);
  const double length = glm::length(t);
  if (!(length > 1e-6 * glm::length(dpdu))) return normal;
  const glm::dvec3 tangent = t / length;
  // glTF's v runs down the image and its maps' +Y is up: B = n x T points against dp/dv where
  // the coordinates are laid out as usual (dp/du x dp/dv opposite n), and is negated where they
  // are mirrored.
  const double handedness = glm::dot(glm::cross(dpdu, dpdv), normal) < 0.0 ? 1.0 : -1.0;
  const glm::dvec3 bitangent = glm::cross(normal, tangent) * handedness;
  return glm::normalize(tangent * mapped.x + bitangent * mapped.y + normal * mapped.z);
}

GBufferSample surfaceAt(const Scene& scene, uint32_t triangle, glm::dvec2 barycentrics,
                        glm::dvec3 rayDir, BackFaces backFaces) {
  uint32_t idx[3];
  glm::dvec3 pos[3], nrm[3];
  glm::dvec2 uv[3];
  for (int k = 0; k < 3; ++k) {
    idx[k] = scene.indices[3 * size_t{triangle} + k];
    pos[k] = scene.positions[idx[k]];
    nrm[k] = scene.normals[idx[k]];
    uv[k] = idx[k] < scene.uvs.size() ? glm::dvec2(scene.uvs[idx[k]]) : glm::dvec2(0.0);
  }
  const glm::dvec2 bc = barycentrics;
  const double w0 = 1.0 - bc.x - bc.y;
  const glm::dvec2 texcoord = uv[0] * w0 + uv[1] * bc.x + uv[2] * bc.y;
  GBufferSample s;
  s.depth = 0.0f;
  s.normal = glm::normalize(nrm[0] * w0 + nrm[1] * bc.x + nrm[2] * bc.y);
  const Material& m = scene.materials[scene.triangleMaterial[triangle]];
  // KHR_texture_transform, as gbuffer_resolve.comp applies it.
  const auto transform = [](const TextureTransform& t, glm::dvec2 coordinates) {
    const glm::dvec3 uv1(coordinates, 1.0);
    return glm::dvec2(glm::dot(t.rowU(), uv1), glm::dot(t.rowV(), uv1));
  };
  const auto transformed = [&](const TextureTransform& t) { return transform(t, texcoord); };
  // The normal map perturbs the front's normal; a back face then shows its negation.
  if (m.normalTexture >= 0) {
    const glm::dvec4 texel =
        sampleBilinear(scene.textures[m.normalTexture], transformed(m.normalTransform), false);
    const glm::dvec3 mapped = glm::dvec3(texel) * 2.0 - 1.0;
    const glm::dvec2 mappedUvs[3] = {transform(m.normalTransform, uv[0]),
                                     transform(m.normalTransform, uv[1]),
                                     transform(m.normalTransform, uv[2])};
    s.normal =
        perturbedNormal(s.normal, pos, mappedUvs,
                        glm::dvec3(mapped.x * m.normalScale, mapped.y * m.normalScale, mapped.z));
  }
  const bool back = glm::dot(glm::cross(pos[1] - pos[0], pos[2] - pos[0]), rayDir) > 0.0;
  if (back) s.normal = -s.normal;

  if (back && backFaces == BackFaces::PerMaterial && !m.doubleSided) {
    s.roughness = 1.0;  // black: diffuse, F0, F90 and emission stay 0
    return s;
  }
  s.emission = glm::dvec3(m.emissiveFactor);
  if (m.emissiveTexture >= 0)
    s.emission *= glm::dvec3(
        sampleBilinear(scene.textures[m.emissiveTexture], transformed(m.emissiveTransform), true));
  glm::dvec4 base(m.baseColorFactor);
  if (m.baseColorTexture >= 0)
    base *=
        sampleBilinear(scene.textures[m.baseColorTexture], transformed(m.baseColorTransform), true);
  double metallic = m.metallicFactor, roughness = m.roughnessFactor;
  if (m.metallicRoughnessTexture >= 0) {
    glm::dvec4 mr = sampleBilinear(scene.textures[m.metallicRoughnessTexture],
                                   transformed(m.metallicRoughnessTransform), false);
    roughness *= mr.g;  // glTF packing: G = roughness, B = metallic
    metallic *= mr.b;
  }
  metallic = std::clamp(metallic, 0.0, 1.0);
  s.roughness = std::clamp(roughness, 0.0, 1.0);
  s.diffuse = glm::dvec3(base) * (1.0 - metallic);
  // KHR_materials_specular scales the dielectric's F0 and F90 (gbuffer_resolve.comp).
  const double strength = m.specularFactor;
  s.f0 = glm::mix(glm::min(0.04 * glm::dvec3(m.specularColorFactor), glm::dvec3(1.0)) * strength,
                  glm::dvec3(base), metallic);
  s.f90 = strength + (1.0 - strength) * metallic;
  return s;
}

double srgbToLinear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

GBufferData resolveGBufferReference(const Scene& scene, const View& view,
                                    std::span<const uint64_t> visibility, BackFaces backFaces) {
  if (visibility.size() != size_t{view.width} * view.height)
    throw Error("resolveGBufferReference: " + std::to_string(visibility.size()) +
                " visibility texels for a " + std::to_string(view.width) + "x" +
                std::to_string(view.height) + " view");
  GBufferData g;
  g.width = view.width;
  g.height = view.height;
  g.samples.resize(visibility.size());
  for (uint32_t y = 0; y < view.height; ++y)
    for (uint32_t x = 0; x < view.width; ++x) {
      size_t i = size_t{y} * view.width + x;
      g.samples[i] = resolvePixel(scene, view, x, y, visibility[i], backFaces);
    }
  return g;
}

GBufferData decodeGBuffer(uint32_t width, uint32_t height, std::span<const std::byte> depth,
                          std::span<const std::byte> normal, std::span<const std::byte> diffuse,
                          std::span<const std::byte> specular,
                          std::span<const std::byte> emission) {
  const size_t texels = size_t{width} * height;
  if (depth.size() != texels * 4 || normal.size() != texels * 4 || diffuse.size() != texels * 8 ||
      specular.size() != texels * 8 || (!emission.empty() && emission.size() != texels * 8))
    throw Error("decodeGBuffer: image sizes do not match " + std::to_string(width) + "x" +
                std::to_string(height));
  GBufferData g;
  g.width = width;
  g.height = height;
  g.samples.resize(texels);
  for (size_t i = 0; i < texels; ++i) {
    GBufferSample& s = g.samples[i];
    s.depth = loadTexel<float>(depth, i);
    glm::dvec4 d = halfsToDouble(diffuse, i), f = halfsToDouble(specular, i);
    s.diffuse = glm::dvec3(d);
    s.roughness = d.w;
    s.f0 = glm::dvec3(f);
    s.f90 = f.w;
    if (!emission.empty()) s.emission = glm::dvec3(halfsToDouble(emission, i));
    // The resolve stores a zero normal for background texels; decoding it would invent +Z.
    if (!s.background())
      s.normal = octDecode(glm::dvec2(decodeSnorm16(loadTexel<int16_t>(normal, 2 * i)),
                                      decodeSnorm16(loadTexel<int16_t>(normal, 2 * i + 1))));
  }
  return g;
}

GBufferData readbackGBuffer(Context& ctx, GBuffer& gbuffer) {
  auto depth = gbuffer.depth.readback(ctx);
  auto normal = gbuffer.normal.readback(ctx);
  auto diffuse = gbuffer.diffuse.readback(ctx);
  auto specular = gbuffer.specular.readback(ctx);
  auto emission = gbuffer.emission.readback(ctx);
  return decodeGBuffer(gbuffer.width, gbuffer.height, depth, normal, diffuse, specular, emission);
}

}  // namespace engine
