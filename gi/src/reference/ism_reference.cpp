#include "reference/ism_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/alpha_cutout.h"
#include "engine/orthonormal_basis.h"

namespace gi {

namespace {

glm::dvec3 vertex(IsmPositions positions, IsmIndices indices, uint32_t triangle, int corner) {
  return glm::dvec3(positions[indices[3 * size_t{triangle} + corner]]);
}

double unorm16(uint32_t bits) {
  return static_cast<double>(bits & 0xFFFFu) / 65535.0;
}

}  // namespace

std::vector<double> ismTriangleCdfReference(IsmPositions positions, IsmIndices indices) {
  std::vector<double> cdf(indices.size() / 3);
  double sum = 0.0;
  for (uint32_t t = 0; t < cdf.size(); ++t) {
    const glm::dvec3 a = vertex(positions, indices, t, 0);
    sum += 0.5 * glm::length(glm::cross(vertex(positions, indices, t, 1) - a,
                                        vertex(positions, indices, t, 2) - a));
    cdf[t] = sum;
  }
  return cdf;
}

glm::dvec2 ismR2(uint32_t i) {
  const uint32_t x1 = 0x80000000u + i * ISM_R2_A1;
  const uint32_t x2 = 0x80000000u + i * ISM_R2_A2;
  return glm::dvec2(x1 >> 8, x2 >> 8) / 16777216.0;
}

std::vector<IsmPointReference> ismPointsReference(IsmPositions positions, IsmIndices indices,
                                                  uint32_t pointCount) {
  const std::vector<double> cdf = ismTriangleCdfReference(positions, indices);
  std::vector<IsmPointReference> points(pointCount);
  if (cdf.empty() || !(cdf.back() > 0.0)) return points;
  for (uint32_t i = 0; i < pointCount; ++i) {
    const double target = (i + 0.5) / pointCount * cdf.back();
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), target);
    points[i].triangle =
        static_cast<uint32_t>(std::min<ptrdiff_t>(it - cdf.begin(), std::ssize(cdf) - 1));
    const glm::dvec2 r = ismR2(i);
    const double s = std::sqrt(r.x);
    points[i].bary = glm::dvec2(s * (1.0 - r.y), s * r.y);
  }
  return points;
}

void ismCutPointsReference(std::vector<IsmPointReference>& points, const engine::Scene& scene) {
  const engine::AlphaCutouts cutouts(scene);
  if (!cutouts.any()) return;
  for (IsmPointReference& p : points) {
    if (p.triangle == ISM_NO_TRIANGLE) continue;
    glm::vec2 uv[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = scene.indices[3 * size_t{p.triangle} + k];
      uv[k] = v < scene.uvs.size() ? scene.uvs[v] : glm::vec2(0.0f);
    }
    const glm::vec2 b(std::round(p.bary.x * 65535.0) / 65535.0,
                      std::round(p.bary.y * 65535.0) / 65535.0);
    if (!cutouts.opaqueAt(scene.triangleMaterial[p.triangle], uv, b)) p = IsmPointReference{};
  }
}

glm::dvec4 ismPointPosition(IsmPositions positions, IsmIndices indices,
                            const gpu::IsmPoint& point) {
  if (point.triangle == ISM_NO_TRIANGLE) return glm::dvec4(0.0);
  const glm::dvec3 a = vertex(positions, indices, point.triangle, 0);
  const glm::dvec3 e1 = vertex(positions, indices, point.triangle, 1) - a;
  const glm::dvec3 e2 = vertex(positions, indices, point.triangle, 2) - a;
  return glm::dvec4(a + unorm16(point.bary) * e1 + unorm16(point.bary >> 16) * e2, 1.0);
}

IsmFrameReference ismFrameReference(const gpu::Vsgl& vsgl, double centreOffset) {
  IsmFrameReference f;
  const double wd = vsgl.diffuse.power.a, ws = vsgl.specular.power.a;
  f.lit = wd + ws > 0.0;
  f.axis = glm::dvec3(wd > 0.0 ? vsgl.diffuse.axisSharpness : vsgl.specular.axisSharpness);
  if (f.lit) {
    f.centre =
        (wd * glm::dvec3(vsgl.diffuse.meanVariance) + ws * glm::dvec3(vsgl.specular.meanVariance)) /
            (wd + ws) +
        centreOffset * f.axis;
    f.extent = std::sqrt(std::max(
        (wd * vsgl.diffuse.meanVariance.w + ws * vsgl.specular.meanVariance.w) / (wd + ws), 0.0));
    if (vsgl.visibilityPoint.w > 0.0f)
      f.centre = glm::dvec3(vsgl.visibilityPoint) + centreOffset * f.axis;
  }
  const engine::OrthonormalBasis basis = engine::orthonormalBasis(f.axis);
  f.tangent = basis.tangent;
  f.bitangent = basis.bitangent;
  return f;
}

IsmProjection ismProjectReference(const IsmFrameReference& frame, glm::dvec3 p) {
  IsmProjection out;
  const glm::dvec3 d = p - frame.centre;
  out.distance = glm::length(d);
  if (!(out.distance > 0.0)) return out;
  const glm::dvec3 dir = d / out.distance;
  out.cosAxis = glm::dot(dir, frame.axis);
  out.uv = 0.5 + 0.5 * glm::dvec2(glm::dot(dir, frame.tangent), glm::dot(dir, frame.bitangent)) /
                     (1.0 + out.cosAxis);
  return out;
}

std::vector<double> ismSplatReference(IsmPositions positions, IsmIndices indices,
                                      std::span<const gpu::IsmPoint> points,
                                      std::span<const gpu::Vsgl> vsgls, uint32_t mapSize,
                                      uint32_t pointsPerVsgl, double centreOffset) {
  const size_t tile = size_t{mapSize} * mapSize;
  std::vector<double> atlas(vsgls.size() * tile, kIsmEmptyReference);
  const auto stride = static_cast<uint32_t>(points.size() / pointsPerVsgl);
  for (uint32_t k = 0; k < vsgls.size(); ++k) {
    const IsmFrameReference frame = ismFrameReference(vsgls[k], centreOffset);
    if (!frame.lit) continue;
    const uint32_t offset = ISM_SUBSET_OFFSET(k, stride);
    for (uint32_t j = 0; j < pointsPerVsgl; ++j) {
      const glm::dvec4 p = ismPointPosition(positions, indices, points[offset + j * stride]);
      if (p.w == 0.0) continue;
      const IsmProjection proj = ismProjectReference(frame, glm::dvec3(p));
      if (!(proj.cosAxis > 0.0)) continue;
      const auto x = std::min(static_cast<uint32_t>(proj.uv.x * mapSize), mapSize - 1);
      const auto y = std::min(static_cast<uint32_t>(proj.uv.y * mapSize), mapSize - 1);
      double& texel = atlas[k * tile + size_t{y} * mapSize + x];
      if (texel == kIsmEmptyReference || proj.distance < texel) texel = proj.distance;
    }
  }
  return atlas;
}

std::vector<double> ismPullPushReference(std::span<const double> raw, uint32_t mapSize,
                                         uint32_t vsglCount) {
  const size_t tile = size_t{mapSize} * mapSize;
  std::vector<double> out(raw.begin(), raw.begin() + vsglCount * tile);
  for (uint32_t k = 0; k < vsglCount; ++k) {
    // levels[0] = the tile, levels[l] = (mapSize >> l)^2 texels; -1 = no valid depth.
    std::vector<std::vector<double>> levels{
        std::vector<double>(out.begin() + k * tile, out.begin() + (k + 1) * tile)};
    for (uint32_t size = mapSize / 2; size >= 1; size /= 2) {
      const std::vector<double>& fine = levels.back();
      std::vector<double> coarse(size_t{size} * size);
      for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
          double sum = 0.0;
          int count = 0;
          for (uint32_t c = 0; c < 4; ++c) {
            const double v = fine[(2 * y + c / 2) * (2 * size) + 2 * x + c % 2];
            if (v >= 0.0) {
              sum += v;
              ++count;
            }
          }
          coarse[y * size + x] = count > 0 ? sum / count : -1.0;
        }
      levels.push_back(std::move(coarse));
    }
    if (levels.back()[0] < 0.0) {  // no point in the whole tile
      std::fill(out.begin() + k * tile, out.begin() + (k + 1) * tile,
                std::numeric_limits<double>::infinity());
      continue;
    }
    for (size_t l = levels.size() - 1; l >= 1; --l) {
      const auto size = static_cast<int>(mapSize >> l);  // coarse size
      const std::vector<double>& coarse = levels[l];
      std::vector<double>& fine = levels[l - 1];
      auto at = [&](int x, int y) {
        return coarse[std::clamp(y, 0, size - 1) * size + std::clamp(x, 0, size - 1)];
      };
      for (int y = 0; y < 2 * size; ++y)
        for (int x = 0; x < 2 * size; ++x) {
          double& v = fine[y * 2 * size + x];
          if (v >= 0.0) continue;
          // Fine texel centre in coarse texel coordinates: x / 2 - 1/4.
          const int x0 = static_cast<int>(std::floor((x - 1) / 2.0));
          const int y0 = static_cast<int>(std::floor((y - 1) / 2.0));
          const double wx = x % 2 == 0 ? 0.75 : 0.25, wy = y % 2 == 0 ? 0.75 : 0.25;
          const double bottom = at(x0, y0) * (1.0 - wx) + at(x0 + 1, y0) * wx;
          const double top = at(x0, y0 + 1) * (1.0 - wx) + at(x0 + 1, y0 + 1) * wx;
          v = bottom * (1.0 - wy) + top * wy;
        }
    }
    std::copy(levels[0].begin(), levels[0].end(), out.begin() + k * tile);
  }
  return out;
}

double ismVisibilityReference(std::span<const double> atlas, const gpu::IsmParams& params,
                              const IsmFrameReference& frame, uint32_t vsglIndex,
                              glm::dvec3 position, glm::dvec3 normal) {
  if (!frame.lit) return 1.0;
  const IsmProjection proj = ismProjectReference(frame, position);
  if (!(proj.cosAxis > 0.0))
    return std::clamp(1.0 + proj.cosAxis * proj.distance / std::max(frame.extent, 1e-6), 0.0, 1.0);
  const auto size = static_cast<int>(params.mapSize);
  const glm::dvec3 dir = (position - frame.centre) / proj.distance;
  const double cosReceiver = std::max(-glm::dot(normal, dir), 0.0);
  const double tanReceiver =
      cosReceiver > 0.0
          ? std::min(std::sqrt(std::max(1.0 - cosReceiver * cosReceiver, 0.0)) / cosReceiver,
                     double(ISM_MAX_SLOPE))
          : 0.0;
  const double footprint = proj.distance * 2.0 * (1.0 + proj.cosAxis) / size;
  const double ref = proj.distance - params.depthBias - params.slopeBias * footprint * tanReceiver;
  const size_t tileBase = size_t{vsglIndex} * size * size;
  auto test = [&](int x, int y) {
    x = std::clamp(x, 0, size - 1);
    y = std::clamp(y, 0, size - 1);
    return ref <= atlas[tileBase + size_t(y) * size + x] ? 1.0 : 0.0;
  };
  const int nx = static_cast<int>(proj.uv.x * size), ny = static_cast<int>(proj.uv.y * size);
  if (params.pcf == ISM_PCF_NEAREST) return test(nx, ny);
  if (params.pcf == ISM_PCF_BOX3) {
    double sum = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) sum += test(nx + dx, ny + dy);
    return sum / 9.0;
  }
  const glm::dvec2 x = proj.uv * double(size) - 0.5;  // bilinear over the texel centres
  const glm::dvec2 t = glm::floor(x);
  const glm::dvec2 w = x - t;
  const int tx = static_cast<int>(t.x), ty = static_cast<int>(t.y);
  const double bottom = test(tx, ty) * (1.0 - w.x) + test(tx + 1, ty) * w.x;
  const double top = test(tx, ty + 1) * (1.0 - w.x) + test(tx + 1, ty + 1) * w.x;
  return std::min(bottom * (1.0 - w.y) + top * w.y, 1.0);
}

bool ismRayCastVisible(IsmPositions positions, IsmIndices indices, glm::dvec3 from, glm::dvec3 to,
                       double endTolerance) {
  const glm::dvec3 d = to - from;
  const double length = glm::length(d);
  if (!(length > 2.0 * endTolerance)) return true;
  const glm::dvec3 dir = d / length;
  for (uint32_t t = 0; t < indices.size() / 3; ++t) {
    // Moller-Trumbore, both faces.
    const glm::dvec3 a = vertex(positions, indices, t, 0);
    const glm::dvec3 e1 = vertex(positions, indices, t, 1) - a;
    const glm::dvec3 e2 = vertex(positions, indices, t, 2) - a;
    const glm::dvec3 p = glm::cross(dir, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-300) continue;
    const glm::dvec3 s = from - a;
    const double u = glm::dot(s, p) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(dir, q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double hit = glm::dot(e2, q) / det;
    if (hit > endTolerance && hit < length - endTolerance) return false;
  }
  return true;
}

}  // namespace gi
