// Environment shading by filtered importance sampling (docs/techniques/environment.md, pass 3;
// vsgl-math.md sections 5.1 and 10): per G-buffer pixel, N Hammersley samples of the BRDF lobe
// read from the dual-paraboloid map (shared/environment.h) at the FIS level, plus the SH
// irradiance for the diffuse term, into the indirect diffuse and glossy images (RGBA32F, linear
// radiance toward the camera). CPU twin: gi/src/reference/env_fis_reference.h (the weights).
#ifndef SHADERS_SHARED_ENV_FIS_H
#define SHADERS_SHARED_ENV_FIS_H
#include "interop.h"

#define ENV_FIS_GROUP_X 8
#define ENV_FIS_GROUP_Y 8

// Mode: specialization constant 0 (lavapipe runs both sides of a branch on a uniform value,
// so each variant is compiled without the others' code).
#define ENV_FIS_FILTERED 0u    // each sample at l = max(log4(K S^2 / (N p r)), 0)
#define ENV_FIS_UNFILTERED 1u  // level 0: the aliasing the filter removes
#define ENV_FIS_RANDOMISED 2u  // level 0, the Hammersley set Cranley-Patterson rotated per pixel
#define ENV_FIS_MODES 3u
// Glossy lobe: specialization constant 1.
#define ENV_FIS_GGX 0u    // the G-buffer's GGX (common/brdf.glsl), weight F G2 (v.h) / (nv n.h)
#define ENV_FIS_PHONG 1u  // normalised Phong around the mirror, e = 2 / alpha^2 - 2, weight F0
#define ENV_FIS_WARD 2u   // Ward half-vector lobe, alpha_x = alpha, alpha_y = alpha * ratio
#define ENV_FIS_BRDFS 3u

SHARED_BEGIN

struct EnvFisPush {
  mat4 invViewProjRelative;  // camera NDC -> offset from the eye (engine::relativeUnprojection)
  uvec2 viewport;
  uint sampleCount;    // N [1, 4096]; 40 is the papers' real-time budget
  uint mapSize;        // S: texels per side of level 0 of one layer
  uint levelCount;     // the map's mip levels (log2 S + 1)
  float kernelExtent;  // K of the level rule [texels]; 4 = [S1]'s +1 level bias, best for box mips
  // ENV_FIS_WARD: alpha_y / alpha_x, (0, inf); 1 = isotropic.
  float wardAnisotropy;
  uint pad0;
};

SHARED_END

SHARED_ASSERT_SIZE(EnvFisPush, 96);
#endif
