#include "reference/env_map_reference.h"

#include <bit>
#include <cmath>
#include <string>

#include "engine/error.h"
#include "reference/env_paraboloid.h"

namespace gi {

namespace {

constexpr uint32_t kLayers = 2;

void checkSize(uint32_t size) {
  if (size == 0 || !std::has_single_bit(size))
    throw engine::Error("environment map: size " + std::to_string(size) + " is not a power of two");
}

// An empty map of `size` with every level allocated.
EnvMapReference allocate(uint32_t size) {
  EnvMapReference map;
  map.size = size;
  const uint32_t levels = static_cast<uint32_t>(std::bit_width(size));
  map.levels.resize(levels);
  for (uint32_t level = 0; level < levels; ++level) {
    const size_t n = size >> level;
    map.levels[level].assign(kLayers * n * n, glm::dvec3(0.0));
  }
  return map;
}

// Level 0: texel (x, y) of layer `layer` covers s in [x, x + 1] / n, t in [y, y + 1] / n (row y
// is t, as Vulkan addresses images); its value is the mean of `radiance` at the directions of
// the four points (x + {1/4, 3/4}, y + {1/4, 3/4}) / n, summed as (s00 + s10) + (s01 + s11),
// the order the conversion shader uses. Texels outside the disc get their directions of the
// other hemisphere, as paraboloidToDirection gives them.
template <class Radiance>
void fillLevel0(EnvMapReference& map, const Radiance& radiance) {
  const uint32_t n = map.size;
  for (uint32_t layer = 0; layer < kLayers; ++layer)
    for (uint32_t y = 0; y < n; ++y)
      for (uint32_t x = 0; x < n; ++x) {
        glm::dvec3 rows[2];
        for (uint32_t j = 0; j < 2; ++j) {
          glm::dvec3 sum(0.0);
          for (uint32_t i = 0; i < 2; ++i) {
            const glm::dvec2 st((x + 0.25 + 0.5 * i) / n, (y + 0.25 + 0.5 * j) / n);
            sum += radiance(paraboloidToDirection(st, layer));
          }
          rows[j] = sum;
        }
        map.levels[0][(size_t{layer} * n + y) * n + x] = (rows[0] + rows[1]) * 0.25;
      }
}

// Levels 1..: exact 2x2 box means of the level above, per layer (shared/mip_reduce.h).
void buildMips(EnvMapReference& map) {
  for (uint32_t level = 1; level < map.levels.size(); ++level) {
    const uint32_t n = map.levelSize(level), parent = map.levelSize(level - 1);
    for (uint32_t layer = 0; layer < kLayers; ++layer)
      for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
          const auto at = [&](uint32_t px, uint32_t py) {
            return map.levels[level - 1][(size_t{layer} * parent + py) * parent + px];
          };
          const glm::dvec3 top = at(2 * x, 2 * y) + at(2 * x + 1, 2 * y);
          const glm::dvec3 bottom = at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1);
          map.levels[level][(size_t{layer} * n + y) * n + x] = (top + bottom) * 0.25;
        }
  }
}

}  // namespace

glm::dvec3 equirectBilinear(const engine::ImageRgba32f& equirect, glm::dvec2 uv) {
  const int w = equirect.width, h = equirect.height;
  const auto texel = [&](int x, int y) {
    const float* p = &equirect.pixels[(size_t(y) * size_t(w) + size_t(x)) * 4];
    return glm::dvec3(p[0], p[1], p[2]);
  };
  // Texel centres at (i + 1/2) / w: the position in texel units relative to the centres.
  const double px = uv.x * w - 0.5, py = uv.y * h - 0.5;
  const double fx0 = std::floor(px), fy0 = std::floor(py);
  const double fx = px - fx0, fy = py - fy0;
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  const auto wrap = [w](int x) { return ((x % w) + w) % w; };
  const auto clampRow = [h](int y) { return y < 0 ? 0 : (y >= h ? h - 1 : y); };
  const int xa = wrap(x0), xb = wrap(x0 + 1), ya = clampRow(y0), yb = clampRow(y0 + 1);
  const glm::dvec3 top = texel(xa, ya) * (1.0 - fx) + texel(xb, ya) * fx;
  const glm::dvec3 bottom = texel(xa, yb) * (1.0 - fx) + texel(xb, yb) * fx;
  return top * (1.0 - fy) + bottom * fy;
}

EnvMapReference envMapFromFunction(uint32_t size,
                                   const std::function<glm::dvec3(glm::dvec3)>& radiance) {
  checkSize(size);
  EnvMapReference map = allocate(size);
  fillLevel0(map, radiance);
  buildMips(map);
  return map;
}

EnvMapReference envMapFromEquirect(const engine::ImageRgba32f& equirect, uint32_t size) {
  checkSize(size);
  if (equirect.width <= 0 || equirect.height <= 0 ||
      equirect.pixels.size() != size_t(equirect.width) * size_t(equirect.height) * 4)
    throw engine::Error("environment map: the equirectangular image is empty or its pixel count " +
                        std::to_string(equirect.pixels.size()) + " is not 4 x " +
                        std::to_string(equirect.width) + " x " + std::to_string(equirect.height));
  EnvMapReference map = allocate(size);
  fillLevel0(map, [&](glm::dvec3 direction) {
    return equirectBilinear(equirect, equirectFromDirection(direction));
  });
  buildMips(map);
  return map;
}

ShRgb envMapSh(const EnvMapReference& map, uint32_t level) {
  if (level >= map.levels.size())
    throw engine::Error("environment map: SH level " + std::to_string(level) + " of a map with " +
                        std::to_string(map.levels.size()) + " levels");
  const uint32_t n = map.levelSize(level);
  std::vector<RadianceSample> samples;
  samples.reserve(size_t{kLayers} * n * n);
  for (uint32_t layer = 0; layer < kLayers; ++layer)
    for (uint32_t y = 0; y < n; ++y)
      for (uint32_t x = 0; x < n; ++x) {
        const double solidAngle = envMapTexelSolidAngle(n, layer, x, y);
        if (solidAngle == 0.0) continue;
        RadianceSample sample;
        sample.direction = paraboloidToDirection({(x + 0.5) / n, (y + 0.5) / n}, layer);
        sample.radiance = map.texel(level, layer, x, y);
        sample.solidAngle = solidAngle;
        samples.push_back(sample);
      }
  return shProjectRadiance(samples);
}

}  // namespace gi
