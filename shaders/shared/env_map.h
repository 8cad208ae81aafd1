// The environment conversion passes (docs/techniques/environment.md, passes 1 and 2): push
// constants and group sizes of shaders/gi/env_paraboloid.comp (equirectangular image -> level 0
// of the dual-paraboloid map of shared/environment.h), shaders/gi/env_mip_reduce.comp (its box
// mips, both layers per dispatch) and shaders/gi/env_sh.comp (9 SH coefficients of one level).
// Host: gi/src/passes/env_map.cpp; CPU twin: gi/src/reference/env_map_reference.cpp.
#ifndef SHADERS_SHARED_ENV_MAP_H
#define SHADERS_SHARED_ENV_MAP_H
#include "interop.h"

#define ENV_CONVERT_GROUP_X 8
#define ENV_CONVERT_GROUP_Y 8
#define ENV_MIP_GROUP_X 8
#define ENV_MIP_GROUP_Y 8
// The SH projection runs as ONE work group of this many threads (a reduction in shared memory:
// 27 floats per thread, 13.5 KiB), over the level whose size is ENV_SH_LEVEL_SIZE (or level 0
// of a smaller map): 2 x 64^2 = 8192 texels, 64 per thread.
#define ENV_SH_GROUP_SIZE 128
#define ENV_SH_LEVEL_SIZE 64
// A texel's solid angle in the SH projection: the midpoint rule on this many points per side,
// counting only those in the layer's own hemisphere (gi::envMapTexelSolidAngle), so that rim
// texels count their own hemisphere's part once; the CPU side reads this define too.
#define ENV_SH_TEXEL_SAMPLES 4

SHARED_BEGIN

struct EnvConvertPush {
  uvec2 equirectSize;  // texels of the equirectangular source (width, height)
  uint mapSize;        // S: texels per side of level 0 of each layer (a power of two)
  uint pad0;
};

struct EnvMipPush {
  uvec2 dstSize;  // texels of the level being written (per layer)
  uint pad0;
  uint pad1;
};

struct EnvShPush {
  uint levelSize;  // n: texels per side of the level that is projected
  uint pad0;
  uint pad1;
  uint pad2;
};

SHARED_END

SHARED_ASSERT_SIZE(EnvConvertPush, 16);
SHARED_ASSERT_SIZE(EnvMipPush, 16);
SHARED_ASSERT_SIZE(EnvShPush, 16);
#endif
