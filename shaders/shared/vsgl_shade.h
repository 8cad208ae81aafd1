// VSGL shading (vsgl-math.md section 4.5): for each G-buffer pixel, the sum over VSGLs and their
// two lobes of the analytic SG lighting, split into indirect diffuse and indirect glossy images
// (RGBA32F, linear radiance), times the ISM visibility when enabled.
#ifndef SHADERS_SHARED_VSGL_SHADE_H
#define SHADERS_SHARED_VSGL_SHADE_H
#include "interop.h"
#include "ism.h"

#define VSGL_SHADE_GROUP_X 8
#define VSGL_SHADE_GROUP_Y 8
// Flags: which terms to shade. They are the pass's specialization constant 0, not a push
// constant, so that a term switched off is compiled out: lavapipe runs both sides of a branch on
// a uniform value (measured: the glossy term cost the same switched off as on).
#define VSGL_SHADE_GLOSSY 1u      // the GGX term (off: the glossy image is 0)
#define VSGL_SHADE_VISIBILITY 2u  // ISM visibility per pixel-VSGL pair (off: 1)
#define VSGL_SHADE_SKIP_SKY 4u    // subgroups that see only sky skip the VSGL loop
// Shade the texels of one level's adaptive-shading queue (shared/adaptive_shading.h) instead of
// every pixel: 1-D groups of ADAPTIVE_QUEUE_GROUP, dispatched indirectly from the queue's head.
#define VSGL_SHADE_QUEUE 8u
// The VSGLs' specular lobes are left out: they carry no power (no surface has a specular lobe,
// the effect planner's SceneGeometry::maxSpecular = 0), so they would add exactly 0.
#define VSGL_SHADE_DIFFUSE_LOBES 16u
// VSGL culling (docs/techniques/vsgl-culling.md): per subgroup, VSGLs whose bound adds up to at
// most VsglShadePush::cullBudget of the least light gathered so far are skipped; counts in
// VsglShadeStats.
#define VSGL_SHADE_CULL 32u
// Planar emitters (docs/techniques/planar-emitters.md, Settings::planarEmitters): flat clusters
// emit no light below or along their plane and are seen foreshortened. Off: the SG emitter of
// vsgl-math.md section 3.4 for every VSGL.
#define VSGL_SHADE_PLANAR 64u
#define VSGL_SHADE_VARIANTS 128u  // every combination of the flags
// Incoming-radiance log amplitudes are clamped here before exp(): e^80 ~ 5.5e34 keeps a
// receiver touching a zero-variance lobe finite (vsgl-math.md section 12, case 12) and, unlike
// +inf, never turns into NaN when multiplied by a zero lighting integral.
#define VSGL_SHADE_MAX_LOG_RADIANCE 80.0

SHARED_BEGIN

struct VsglShadePush {
  mat4 invViewProjRelative;  // camera NDC -> offset from `eye` (engine::relativeUnprojection)
  vec3 eye;  // the camera's position, world
  // VSGL_SHADE_CULL's budget tau: the fraction of a pixel's light that the skipped VSGLs may
  // bound (it fills the 16 bytes of `eye`'s row).
  float cullBudget;
  uvec2 viewport;
  uint vsglCount;
  IsmParams ism;  // the atlas's layout and biases (read with VSGL_SHADE_VISIBILITY)
  // VSGL_SHADE_QUEUE: the queue's level. Above level 0 the outputs are that level's images:
  // diffuse without the albedo, alpha = the level.
  uint level;
};

// VSGL_SHADE_CULL's counts, per level (0 = full rate): subgroup x VSGL tests, and of those the
// VSGLs skipped. Zeroed by the host before the frame's first shading pass.
struct VsglShadeStats {
  uint tested[4];
  uint skipped[4];
};

SHARED_END

SHARED_ASSERT_SIZE(VsglShadePush, 128);
SHARED_ASSERT_OFFSET(VsglShadePush, cullBudget, 76);
SHARED_ASSERT_SIZE(VsglShadeStats, 32);
#endif
