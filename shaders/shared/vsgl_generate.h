// Push constants of vsgl_generate.comp ("filtered sampling" in [S3] Table 1).
#ifndef SHADERS_SHARED_VSGL_GENERATE_H
#define SHADERS_SHARED_VSGL_GENERATE_H
#include "interop.h"

#define VSGL_GENERATE_GROUP 64

SHARED_BEGIN

struct VsglGeneratePush {
  vec4 origin;        // xyz = RSM origin (world), added to every mean
  uint count;         // N, VSGLs to generate
  uint rule;          // VSGL_RULE_TOK15 or VSGL_RULE_MODIFIED
  uint size;          // pyramid base size (power of two)
  uint topLevel;      // log2(size)
  float kernelScale;  // K (paper: 1); larger = blurrier, temporally steadier kernels
  uint pad0;
  uint pad1;
  uint pad2;
};

SHARED_END

SHARED_ASSERT_SIZE(VsglGeneratePush, 48);
#endif
