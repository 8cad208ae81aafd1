#include "engine/raster_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "engine/alpha_cutout.h"
#include "engine/rasterizer.h"
#include "shared/raster.h"

namespace engine {
namespace {

constexpr int kScale = static_cast<int>(RASTER_SUBPIXEL_SCALE);

// The alpha test of one source triangle, as raster_triangles.comp stages it (stageCutout).
struct Cutout {
  const AlphaCutouts* cutouts = nullptr;  // null: the triangle is not tested
  uint32_t material = 0;
  glm::vec3 edge[3];
  glm::vec2 uv[3];
};

struct Rasterization {
  uint32_t width;
  uint32_t height;
  uint32_t triangleId;
  ReferenceRaster* out;
  Cutout cutout;
};

float planeDistance(const glm::vec4& v, int k) {
  float g = static_cast<float>(RASTER_GUARD_BAND) * v.w;
  switch (k) {
    case 0:
      return v.z;
    case 1:
      return g - v.x;
    case 2:
      return g + v.x;
    case 3:
      return g - v.y;
    default:
      return g + v.y;
  }
}

glm::vec4 intersectEdge(const glm::vec4& inside, float dIn, const glm::vec4& outside, float dOut) {
  float t = dIn / (dIn - dOut);
  glm::vec4 r;
  for (int k = 0; k < 4; ++k) r[k] = inside[k] + (outside[k] - inside[k]) * t;
  return r;
}

glm::ivec2 toFixed(const Rasterization& c, const glm::vec4& v) {
  glm::ivec2 r;
  for (int k = 0; k < 2; ++k) {
    float ndc = v[k] / v.w;
    float extent = static_cast<float>(k == 0 ? c.width : c.height);
    float screen = (ndc * 0.5f + 0.5f) * extent;
    r[k] = static_cast<int>(std::floor(screen * static_cast<float>(RASTER_SUBPIXEL_SCALE) + 0.5f));
  }
  return r;
}

int64_t edge(glm::ivec2 a, glm::ivec2 b, glm::ivec2 p) {
  return int64_t{b.x - a.x} * int64_t{p.y - a.y} - int64_t{b.y - a.y} * int64_t{p.x - a.x};
}

glm::vec3 crossExact(glm::vec3 a, glm::vec3 b) {
  glm::vec3 r;
  float p = a.y * b.z, q = a.z * b.y;
  r.x = p - q;
  p = a.z * b.x;
  q = a.x * b.z;
  r.y = p - q;
  p = a.x * b.y;
  q = a.y * b.x;
  r.z = p - q;
  return r;
}

// stageCutout(): the source triangle's 2-D homogeneous edge functions and base colour
// coordinates, for a material that is alpha-tested.
Cutout stageCutout(const Scene& scene, const AlphaCutouts& cutouts, const RasterTransform& t,
                   uint32_t width, uint32_t height, uint32_t tri) {
  Cutout c;
  const uint32_t material = scene.triangleMaterial[tri];
  if (!cutouts.tested(material)) return c;
  c.cutouts = &cutouts;
  c.material = material;
  glm::vec3 h[3];
  for (int i = 0; i < 3; ++i) {
    const uint32_t v = scene.indices[3 * size_t{tri} + i];
    const glm::vec4 clip = rasterClip(t, scene.positions[v]);
    const float halfWidth = 0.5f * static_cast<float>(width);
    const float halfHeight = 0.5f * static_cast<float>(height);
    float sx = clip.x + clip.w;
    sx = sx * halfWidth;
    float sy = clip.y + clip.w;
    sy = sy * halfHeight;
    h[i] = glm::vec3(sx, sy, clip.w);
    c.uv[i] = cutouts.coordinates(material, v < scene.uvs.size() ? scene.uvs[v] : glm::vec2(0.0f));
  }
  c.edge[0] = crossExact(h[1], h[2]);
  c.edge[1] = crossExact(h[2], h[0]);
  c.edge[2] = crossExact(h[0], h[1]);
  return c;
}

// cutoutKeeps(): whether the surface exists at sample s (fixed point).
bool cutoutKeeps(const Cutout& c, glm::ivec2 s) {
  const float px = static_cast<float>(s.x) * (1.0f / static_cast<float>(RASTER_SUBPIXEL_SCALE));
  const float py = static_cast<float>(s.y) * (1.0f / static_cast<float>(RASTER_SUBPIXEL_SCALE));
  float l[3];
  for (int i = 0; i < 3; ++i) {
    const float a = c.edge[i].x * px;
    const float b = c.edge[i].y * py;
    const float sum = a + b;
    l[i] = sum + c.edge[i].z;
  }
  float sum = l[0] + l[1];
  sum = sum + l[2];
  glm::vec2 uv;
  for (int k = 0; k < 2; ++k) {
    const float a = c.uv[0][k] * l[0];
    const float b = c.uv[1][k] * l[1];
    const float d = c.uv[2][k] * l[2];
    float n = a + b;
    n = n + d;
    uv[k] = n / sum;
  }
  return c.cutouts->opaque(c.material, uv);
}

int64_t fillBias(glm::ivec2 a, glm::ivec2 b) {
  glm::ivec2 d = b - a;
  bool topLeft = d.y < 0 || (d.y == 0 && d.x > 0);
  return topLeft ? 0 : -1;
}

void emit(Rasterization& c, glm::vec4 c0, glm::vec4 c1, glm::vec4 c2) {
  glm::ivec2 p0 = toFixed(c, c0), p1 = toFixed(c, c1), p2 = toFixed(c, c2);
  float z0 = c0.z / c0.w, z1 = c1.z / c1.w, z2 = c2.z / c2.w;
  int64_t area = edge(p0, p1, p2);
  if (area == 0) return;
  if (area < 0) {
    std::swap(p1, p2);
    std::swap(z1, z2);
  }
  glm::ivec2 lo = glm::min(glm::min(p0, p1), p2), hi = glm::max(glm::max(p0, p1), p2);
  glm::ivec2 pixLo = (lo - kScale / 2 + kScale - 1) >> RASTER_SUBPIXEL_BITS;
  glm::ivec2 pixHi = (hi - kScale / 2) >> RASTER_SUBPIXEL_BITS;
  pixLo = glm::max(pixLo, glm::ivec2(0));
  pixHi = glm::min(pixHi, glm::ivec2(c.width, c.height) - 1);
  for (int y = pixLo.y; y <= pixHi.y; ++y) {
    for (int x = pixLo.x; x <= pixHi.x; ++x) {
      glm::ivec2 s(x * kScale + kScale / 2, y * kScale + kScale / 2);
      int64_t e0 = edge(p1, p2, s), e1 = edge(p2, p0, s), e2 = edge(p0, p1, s);
      if (e0 + fillBias(p1, p2) < 0 || e1 + fillBias(p2, p0) < 0 || e2 + fillBias(p0, p1) < 0)
        continue;
      size_t pixel = static_cast<size_t>(y) * c.width + x;
      float a = static_cast<float>(e0) * z0;
      float b = static_cast<float>(e1) * z1;
      float d = static_cast<float>(e2) * z2;
      float sum = a + b;
      sum = sum + d;
      float z = sum / static_cast<float>(e0 + e1 + e2);
      const bool kept = !c.cutout.cutouts || cutoutKeeps(c.cutout, s);
      if (kept) c.out->coverage[pixel]++;
      if (!(z >= 0.0f && z <= 1.0f) || !kept) continue;
      uint64_t packed = (uint64_t{std::bit_cast<uint32_t>(z)} << 32) | c.triangleId;
      c.out->visibility[pixel] = std::min(c.out->visibility[pixel], packed);
    }
  }
}

}  // namespace

ReferenceRaster rasterizeReference(const Scene& scene, const glm::mat4& viewProj, uint32_t width,
                                   uint32_t height) {
  return rasterizeReference(scene, rasterTransform(viewProj), width, height);
}

ReferenceRaster rasterizeReference(const Scene& scene, const RasterTransform& transform,
                                   uint32_t width, uint32_t height) {
  ReferenceRaster out;
  out.visibility.assign(size_t{width} * height, ~uint64_t{0});
  out.coverage.assign(size_t{width} * height, 0);
  Rasterization c{width, height, 0, &out, {}};
  const AlphaCutouts cutouts(scene);
  for (uint32_t tri = 0; tri < scene.triangleCount(); ++tri) {
    c.triangleId = tri;
    glm::vec4 v[3];
    for (int i = 0; i < 3; ++i)
      v[i] = rasterClip(transform, scene.positions[scene.indices[3 * tri + i]]);
    bool rejected = false;
    for (int axis = 0; axis < 2; ++axis) {
      rejected = rejected || (v[0][axis] > v[0].w && v[1][axis] > v[1].w && v[2][axis] > v[2].w);
      rejected = rejected || (v[0][axis] < -v[0].w && v[1][axis] < -v[1].w && v[2][axis] < -v[2].w);
    }
    rejected = rejected || (v[0].z < 0.0f && v[1].z < 0.0f && v[2].z < 0.0f);
    rejected = rejected || (v[0].z > v[0].w && v[1].z > v[1].w && v[2].z > v[2].w);
    if (rejected) continue;
    c.cutout =
        cutouts.any() ? stageCutout(scene, cutouts, transform, width, height, tri) : Cutout{};

    bool inside = true;
    for (int k = 0; k < 5; ++k)
      for (int i = 0; i < 3; ++i) inside = inside && planeDistance(v[i], k) >= 0.0f;
    if (inside) {
      emit(c, v[0], v[1], v[2]);
      continue;
    }
    std::vector<glm::vec4> poly(v, v + 3), next;
    for (int k = 0; k < 5 && !poly.empty(); ++k) {
      next.clear();
      for (size_t i = 0; i < poly.size(); ++i) {
        glm::vec4 a = poly[i], b = poly[(i + 1) % poly.size()];
        float da = planeDistance(a, k), db = planeDistance(b, k);
        if (da >= 0.0f) next.push_back(a);
        if ((da >= 0.0f) != (db >= 0.0f))
          next.push_back(da >= 0.0f ? intersectEdge(a, da, b, db) : intersectEdge(b, db, a, da));
      }
      poly.swap(next);
    }
    for (size_t i = 1; i + 1 < poly.size(); ++i) emit(c, poly[0], poly[i], poly[i + 1]);
  }
  return out;
}

}  // namespace engine
