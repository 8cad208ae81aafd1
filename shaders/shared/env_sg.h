// SG lights from the environment (docs/techniques/environment.md, pass 4): the layout of the two
// attribute pyramids of shaders/gi/env_sg_pyramid.comp, the light record that
// shaders/gi/env_sg_generate.comp writes and shaders/gi/env_sg_shade.comp reads, and the push
// constants of the three passes. Host: gi/src/passes/env_sg.cpp; CPU twin:
// gi/src/reference/env_sg_reference.cpp (the estimator and the fit are derived there).
#ifndef SHADERS_SHARED_ENV_SG_H
#define SHADERS_SHARED_ENV_SG_H
#include "interop.h"

#define ENV_SG_PYRAMID_GROUP_X 8
#define ENV_SG_PYRAMID_GROUP_Y 8
#define ENV_SG_GENERATE_GROUP 64
#define ENV_SG_SHADE_GROUP_X 8
#define ENV_SG_SHADE_GROUP_Y 8
// The attribute pyramids: two RGBA32F 2-layer array images of the map's level-0 size, with the
// full box-mean mip chain (levels hold per-texel MEANS; times the texel count they are sums).
// Texel t of layer k, w_t = the solid angle of its part in its own hemisphere (0 outside the
// disc), f_t = its whole solid angle (outside the disc the texel holds real directions of the
// other hemisphere), L_t = the map's level-0 texel, lum = Rec.709 luminance:
//   ENV_SG_RADIANCE:  rgb = f_t L_t,  a = w_t lum(L_t) (the PDF mass m_t: the warp's)
//   ENV_SG_DIRECTION: xyz = lum(L_t) integral over the whole texel of the direction,
//                     w = f_t lum(L_t) (the kernels' mass and the fit's denominator)
#define ENV_SG_RADIANCE 0
#define ENV_SG_DIRECTION 1
#define ENV_SG_PYRAMIDS 2
// w_t and the direction integral by the midpoint rule on this many points per texel side, the
// points inside the layer's own hemisphere only: the rule of gi::envMapTexelSolidAngle (must
// equal ENV_SH_TEXEL_SAMPLES, asserted in gi/src/common/env_texels.cpp), so that every
// direction is counted once.
#define ENV_SG_TEXEL_SAMPLES 4
// The most lights one EnvSgLights generates (its buffer's size) unless told otherwise.
#define ENV_SG_DEFAULT_MAX_COUNT 4096

SHARED_BEGIN

// One distant SG light, L(w) = amplitude G(w; axis, sharpness), w pointing FROM the receiver
// towards the environment. Its integral over the sphere is amplitude S(sharpness).
struct EnvSgLight {
  vec4 axisSharpness;  // xyz unit axis, w sharpness [0, VSGL_MAX_SHARPNESS]
  vec4 amplitude;      // rgb radiance at the peak; a = p~, the kernel's PDF density over the mean
  vec4 kernel;         // xy (s, t) of the kernel centre, z its mip level, w its layer (0 or 1)
};

struct EnvSgPyramidPush {
  uint size;  // texels per side of the map's level 0 (and of the pyramids' level 0)
  uint pad0;
  uint pad1;
  uint pad2;
};

struct EnvSgGeneratePush {
  uint count;         // N lights, [1, max count]
  uint size;          // pyramid level-0 size (a power of two)
  uint topLevel;      // log2(size): the 1 x 1 level
  float kernelScale;  // K [1, N]: each kernel holds K / N of the PDF mass; larger = blurrier
  // 4 pi / sum w_t (gi::envSgOwnSolidAngle): the staircase rim's solid angle rescaled to 4 pi
  float solidAngleScale;
  uint pad0;
  uint pad1;
  uint pad2;
};

struct EnvSgShadePush {
  mat4 invViewProjRelative;  // camera NDC -> offset from the eye (engine::relativeUnprojection)
  uvec2 viewport;
  uint count;  // lights to sum
  uint pad0;
};

SHARED_END

SHARED_ASSERT_SIZE(EnvSgLight, 48);
SHARED_ASSERT_SIZE(EnvSgPyramidPush, 16);
SHARED_ASSERT_SIZE(EnvSgGeneratePush, 32);
SHARED_ASSERT_SIZE(EnvSgShadePush, 80);
#endif
