// Push constants of vsgl_generate.comp ("filtered sampling" in [S3] Table 1).
#ifndef SHADERS_SHARED_VSGL_GENERATE_H
#define SHADERS_SHARED_VSGL_GENERATE_H
#include "interop.h"

#define VSGL_GENERATE_GROUP 64

SHARED_BEGIN

struct VsglGeneratePush {
  vec4 origin;  // xyz = RSM origin (world), added to every mean
  // VSGL_RULE_POINT only, the patch a texel covers: xyz = unit direction the light travels,
  // w = texel area (spot: on the plane at unit distance; directional: m^2), as RsmView.
  vec4 texelPatch;
  uint count;         // N, VSGLs to generate
  uint rule;          // VSGL_RULE_TOK15, VSGL_RULE_MODIFIED or VSGL_RULE_POINT
  uint size;          // pyramid base size (power of two)
  uint topLevel;      // log2(size)
  float kernelScale;  // K (paper: 1); larger = blurrier, temporally steadier kernels
  // VSGL_RULE_POINT only: 1 = spot (perspective RSM), 0 = directional (orthographic).
  uint perspective;
  // 1: this view's first record and count are ranges[view] of the allocation
  // (shared/vsgl_allocation.h), and `count` only bounds them; 0: records [0, count).
  uint ranged;
  uint view;
  // > 0: kernels are shrunk until their mean lies within this many standard deviations of the
  // surface under their centre (gi::Settings::surfaceTolerance); 0: kernels as the rule sizes
  // them.
  float surfaceTolerance;
  uint pad0;
  uint pad1;
  uint pad2;
};

SHARED_END

SHARED_ASSERT_SIZE(VsglGeneratePush, 80);
#endif
