#include "common/env_texels.h"

#include "shared/env_map.h"
#include "shared/env_sg.h"
#include "shared/environment.h"

namespace gi {
namespace {

constexpr double kParaboloidScale = ENV_PARABOLOID_SCALE;
constexpr uint32_t kLayers = 2;
// The SH projection and the SG pyramid count a texel's own-hemisphere part on the same points.
static_assert(ENV_SG_TEXEL_SAMPLES == ENV_SH_TEXEL_SAMPLES,
              "env_sg_pyramid.comp's solid angles differ from env_sh.comp's");

}  // namespace

double envMapTexelSolidAngle(uint32_t n, uint32_t layer, uint32_t x, uint32_t y) {
  // K x K points (x + (i + 1/2) / K, y + (j + 1/2) / K) / n: at each, 2 st - 1 =
  // (2 (K x + i) + 1 - K n) / (K n) is exact, and rho^2 = b^2 |2 st - 1|^2 never ties 1 (that
  // needs (K n)^2 / b^2 = (K n)^2 25 / 36 to be an integer, impossible for K n a power of two),
  // so the fp32 shader classifies every point as double does.
  const uint32_t k = ENV_SH_TEXEL_SAMPLES;
  const double kn = double(k) * n;
  double sum = 0.0;
  for (uint32_t j = 0; j < k; ++j)
    for (uint32_t i = 0; i < k; ++i) {
      const double cx = (2.0 * (k * x + i) + 1.0 - kn) / kn;
      const double cy = (2.0 * (k * y + j) + 1.0 - kn) / kn;
      const double rho2 = kParaboloidScale * kParaboloidScale * (cx * cx + cy * cy);
      if (layer == 0 ? rho2 > 1.0 : rho2 >= 1.0) continue;
      const double onePlusRho2 = 1.0 + rho2;
      sum += 16.0 * kParaboloidScale * kParaboloidScale / (onePlusRho2 * onePlusRho2);
    }
  return sum / (kn * kn);
}

double envSgOwnSolidAngle(uint32_t n) {
  double sum = 0.0;
  for (uint32_t layer = 0; layer < kLayers; ++layer)
    for (uint32_t y = 0; y < n; ++y)
      for (uint32_t x = 0; x < n; ++x) sum += envMapTexelSolidAngle(n, layer, x, y);
  return sum;
}

}  // namespace gi
