#include "room.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/packing.hpp>
#include <limits>

namespace {

struct Quad {
  glm::vec3 corner, edgeU, edgeV;  // counter-clockwise seen from the inside
  glm::vec3 albedo;
};

const Quad kQuads[] = {
    {{-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, {0.8f, 0.8f, 0.8f}},   // floor, +Y
    {{-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, {0.8f, 0.8f, 0.8f}},   // back wall, +Z
    {{-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, {0.8f, 0.1f, 0.1f}},   // left wall, +X
    {{1, 0, -1}, {0, 0, 2}, {0, 2, 0}, {0.1f, 0.8f, 0.1f}},    // right wall, -X
};

glm::vec3 normalOf(const Quad& q) { return glm::normalize(glm::cross(q.edgeU, q.edgeV)); }

// Octahedral encoding (Cigolle et al. 2014), as shared/gbuffer.h specifies the normal image.
glm::vec2 octEncode(glm::vec3 n) {
  glm::vec2 p = glm::vec2(n) / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
  if (n.z > 0.0f) return p;
  const glm::vec2 sign(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
  return (1.0f - glm::abs(glm::vec2(p.y, p.x))) * sign;
}

int16_t snorm16(float v) { return static_cast<int16_t>(std::lround(std::clamp(v, -1.0f, 1.0f) * 32767.0f)); }

}  // namespace

Room makeRoom(float aspect) {
  Room room;
  for (uint32_t q = 0; q < 4; ++q) {
    const Quad& quad = kQuads[q];
    const glm::vec3 n = normalOf(quad);
    const auto base = static_cast<uint32_t>(room.vertices.size());
    for (glm::vec2 uv : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
      room.vertices.push_back({glm::vec4(quad.corner + uv.x * quad.edgeU + uv.y * quad.edgeV, uv.x),
                               glm::vec4(n, uv.y)});
    room.indices.insert(room.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    room.triangleMaterials.insert(room.triangleMaterials.end(), {q, q});
    gpu::SceneMaterial m{};
    m.baseColorFactor = glm::vec4(quad.albedo, 1.0f);
    m.specular = glm::vec4(1.0f);  // KHR_materials_specular's defaults
    m.roughness = 0.8f;
    m.baseColorLayer = m.metallicRoughnessLayer = m.normalLayer = m.emissiveLayer = -1;
    m.doubleSided = 1;
    room.materials.push_back(m);
  }
  // Camera at (0, 1, 3.2) looking down -Z, 0.9 rad vertical field of view, NDC y down, depth
  // [0, 1] from 0.1 m to infinity.
  room.view = glm::lookAt(glm::vec3(0.0f, 1.0f, 3.2f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0, 1, 0));
  const float f = 1.0f / std::tan(0.45f);
  room.proj = glm::mat4(0.0f);
  room.proj[0][0] = f / aspect;
  room.proj[1][1] = -f;
  room.proj[2][2] = -1.0f;
  room.proj[2][3] = -1.0f;
  room.proj[3][2] = -0.1f;
  return room;
}

CpuGBuffer rayCastGBuffer(const Room& room, uint32_t width, uint32_t height) {
  const size_t pixels = size_t{width} * height;
  CpuGBuffer g{std::vector<float>(pixels, 1.0f), std::vector<int16_t>(2 * pixels, 0),
               std::vector<uint16_t>(4 * pixels, 0), std::vector<uint16_t>(4 * pixels, 0),
               std::vector<int>(pixels, -1), std::vector<glm::vec3>(pixels, glm::vec3(0.0f)),
               std::vector<glm::vec3>(pixels, glm::vec3(0.0f))};
  const glm::mat4 viewProj = room.proj * room.view;
  const glm::mat4 inverse = glm::inverse(viewProj);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / glm::vec2(width, height) * 2.0f - 1.0f;
      const glm::vec4 a = inverse * glm::vec4(ndc, 0.0f, 1.0f), b = inverse * glm::vec4(ndc, 0.5f, 1.0f);
      const glm::vec3 origin = glm::vec3(a) / a.w, dir = glm::normalize(glm::vec3(b) / b.w - origin);
      float nearest = std::numeric_limits<float>::infinity();
      const size_t i = size_t{y} * width + x;
      for (int q = 0; q < 4; ++q) {
        const Quad& quad = kQuads[q];
        const glm::vec3 n = normalOf(quad);
        const float t = glm::dot(quad.corner - origin, n) / glm::dot(dir, n);
        if (!(t > 0.0f && t < nearest)) continue;
        const glm::vec3 d = origin + t * dir - quad.corner;
        const float u = glm::dot(d, quad.edgeU) / glm::dot(quad.edgeU, quad.edgeU);
        const float v = glm::dot(d, quad.edgeV) / glm::dot(quad.edgeV, quad.edgeV);
        if (u < 0.0f || u > 1.0f || v < 0.0f || v > 1.0f) continue;
        nearest = t;
        g.quad[i] = q;
        g.position[i] = origin + t * dir;
      }
      if (g.quad[i] < 0) continue;
      const Quad& quad = kQuads[g.quad[i]];
      glm::vec3 n = normalOf(quad);
      if (glm::dot(n, dir) > 0.0f) n = -n;  // facing the viewer
      g.worldNormal[i] = n;
      const glm::vec4 clip = viewProj * glm::vec4(g.position[i], 1.0f);
      g.depth[i] = clip.z / clip.w;
      const glm::vec2 e = octEncode(n);
      g.normal[2 * i] = snorm16(e.x);
      g.normal[2 * i + 1] = snorm16(e.y);
      const glm::vec4 diffuse(quad.albedo, 0.8f), specular(0.04f, 0.04f, 0.04f, 1.0f);
      for (int c = 0; c < 4; ++c) {
        g.diffuse[4 * i + c] = glm::packHalf1x16(diffuse[c]);
        g.specular[4 * i + c] = glm::packHalf1x16(specular[c]);
      }
    }
  return g;
}
