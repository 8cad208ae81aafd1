// Sharing a frame's N VSGLs among the RSM views of its lights (docs/techniques/many-lights.md):
// vsgl_view_weight.comp records each view's weights right after its PDF is built, and
// vsgl_allocate.comp turns them into each view's range of the VSGL buffer, which
// vsgl_generate.comp then reads. The CPU twin is gi/src/reference/vsgl_allocation_reference.cpp.
#ifndef SHADERS_SHARED_VSGL_ALLOCATION_H
#define SHADERS_SHARED_VSGL_ALLOCATION_H
#include "interop.h"

// Views of one frame: kMaxLights lights of up to six views each (a point light's cube faces).
#define VSGL_MAX_VIEWS 48u

SHARED_BEGIN

// Per view: x = the mean reflected power of its texels (luminance weights of both lobes, the
// flux PDF's total over the texel count), y = the mean view importance of that power (the BRSM
// cells' mean; x when the PDF is the flux), zw unused.
struct VsglViewWeight {
  vec4 weight;
};

struct VsglViewWeightPush {
  uint view;  // the slot written, < VSGL_MAX_VIEWS
  uint brsm;  // 1: y from the BRSM cells, 0: y = x
  uint pad0;
  uint pad1;
};

// Per view: x = first record, y = record count.
struct VsglViewRange {
  uvec4 range;
};

struct VsglAllocatePush {
  uint viewCount;  // views this frame, [1, VSGL_MAX_VIEWS]
  uint count;      // N, VSGLs to share
  float fluxMix;   // the PDF's mix with the flux PDF (BrsmSettings::fluxMix); 1 with the flux PDF
  uint pad;
};

SHARED_END

SHARED_ASSERT_SIZE(VsglViewWeight, 16);
SHARED_ASSERT_SIZE(VsglViewWeightPush, 16);
SHARED_ASSERT_SIZE(VsglViewRange, 16);
SHARED_ASSERT_SIZE(VsglAllocatePush, 16);
#endif
