// One level of an exact box-filter mip pyramid: texel (x, y) of level l+1 is the mean of the
// 2x2 texels (2x, 2y) .. (2x+1, 2y+1) of level l. Pyramids are power-of-two squares (smaller
// inputs are padded with zeros), so every level is the exact mean of the texels it covers,
// which the VSGL sums (vsgl-math.md section 3.5) and the PDF normalisation (section 5.3) rely on.
#ifndef SHADERS_SHARED_MIP_REDUCE_H
#define SHADERS_SHARED_MIP_REDUCE_H
#include "interop.h"

#define MIP_GROUP_X 8
#define MIP_GROUP_Y 8

SHARED_BEGIN

struct MipReducePush {
  uvec2 dstSize;  // texels of the level being written
  uint pad0;
  uint pad1;
};

SHARED_END

SHARED_ASSERT_SIZE(MipReducePush, 16);
#endif
