// Environment lighting (docs/techniques/environment.md, vsgl-math.md section 10): the layout of
// the converted environment that every environment pass reads. The map is one RGBA32F 2-layer
// array image of ENV_MAP_SIZE^2 texels per layer with the full box-filtered mip chain: layer 0
// holds the directions with z >= 0, layer 1 those with z < 0, both as the scaled dual paraboloid
// of common/env_paraboloid.glsl (CPU twin gi/src/reference/env_paraboloid.h). The environment's
// own frame is the world's.
#ifndef SHADERS_SHARED_ENVIRONMENT_H
#define SHADERS_SHARED_ENVIRONMENT_H
#include "interop.h"

// [S1] section 20.4: the paraboloid is scaled by b = 1.2 so that the rim of each map's disc
// sits inside the square and a mip texel there averages real directions, not padding.
#define ENV_PARABOLOID_SCALE 1.2
// SH irradiance: 9 coefficients (bands 0-2) per channel.
#define ENV_SH_COEFFICIENTS 9

SHARED_BEGIN

// The environment's 9 SH radiance coefficients (index l (l + 1) + m, real SH without the
// Condon-Shortley phase, gi/src/reference/sh_irradiance.h), rgb used.
struct EnvSh {
  vec4 coefficients[ENV_SH_COEFFICIENTS];
};

SHARED_END

SHARED_ASSERT_SIZE(EnvSh, 144);
#endif
