// Adaptive (multi-resolution) shading, after [S4] section 3.2 (vsgl-math.md section 11): the
// indirect light is shaded coarse to fine on a pyramid of the G-buffer. Level L has one texel per
// 2^L x 2^L pixel block, shaded at the block's representative pixel, its top-left corner
// (adaptiveRepresentative), so that a texel shaded at level L is also the exact light of its
// first child at every finer level: where the child cannot interpolate, it reuses that light
// instead of shading the same pixel again, and no pixel is ever shaded twice.
// Level by level, each texel is either interpolated from its four parents at level L + 1, when
// they and it lie on one surface of one material and the parents' light agrees, or appended to
// the level's queue and shaded (vsgl_shade.comp with VSGL_SHADE_QUEUE). Diffuse light is kept
// without the albedo above level 0 (the irradiance-like sum), so textures stay sharp.
// The decision pass is shaders/gi/adaptive_decide.comp; its CPU twin is
// gi/src/reference/adaptive_reference.cpp.
#ifndef SHADERS_SHARED_ADAPTIVE_SHADING_H
#define SHADERS_SHARED_ADAPTIVE_SHADING_H
#include "interop.h"

#define ADAPTIVE_GROUP_X 8
#define ADAPTIVE_GROUP_Y 8
#define ADAPTIVE_MAX_LEVEL 3u  // coarsest level: 8 x 8 pixels per texel
// Queue entries are texel coordinates packed as x | y << 16 (G-buffers up to 16384 wide).
#define ADAPTIVE_PACK_SHIFT 16u
// The queue is shaded by 1-D groups of this many invocations (the shading pass's group size).
#define ADAPTIVE_QUEUE_GROUP 64u
// A queue entry that pads an ordered group's range (AdaptiveDecidePush::orderedAlign): no texel.
#define ADAPTIVE_QUEUE_EMPTY 0xFFFFFFFFu

SHARED_BEGIN

// The head of one level's queue; the texel entries (uint) follow it in the same buffer. The
// first three words are the VkDispatchIndirectCommand that shades the queue.
struct AdaptiveQueueHeader {
  uint groupsX;       // ceil(entries / ADAPTIVE_QUEUE_GROUP)
  uint groupsY;       // 1
  uint groupsZ;       // 1
  uint shaded;        // entries appended this frame
  uint interpolated;  // texels of this level filled from their parents
  uint reused;        // texels that took their first parent's light, shaded at the same pixel
  uint sky;           // texels whose representative pixel sees the sky
  // Level 0 only: interpolated and reused pixels by the level their light was shaded at
  // (followed through the parent with the largest weight, the diffuse alpha of the levels).
  uint fromLevel[4];
  uint entries;  // entries written: shaded, plus the padding of ordered queues
};

struct AdaptiveDecidePush {
  mat4 invViewProjRelative;  // camera NDC -> offset from the eye (engine::relativeUnprojection)
  uvec2 viewport;            // G-buffer size in pixels
  uint level;                // this pass's level L
  uint coarsest;             // the coarsest level: every texel there is shaded
  // The tests of Settings::adaptive (gi/include/gi/settings.h), in the form the shader uses.
  float planeTolerance;  // |n_parent . (x - x_parent)| <= this x distance to the eye
  float normalCosine;    // n . n_parent >= this
  float roughnessTolerance;
  float f0Tolerance;
  float lightTolerance;  // parents' light: max - min <= this x mean (luminance seen at x)
  // 1: texels whose F0 and F90 are 0 (no glossy term) go to the plain queue, shaded without the
  // glossy term (PlannerSettings::skipGlossyWithoutSpecular).
  uint splitGlossy;
  // 0: texels append themselves to the queues in the order the device runs them. > 0 (VSGL
  // culling on): each decide group appends its texels as one range in invocation order, padded
  // to a multiple of this, the shading pass's largest subgroup size, so that every subgroup
  // that shades the queue holds the same texels in every run.
  uint orderedAlign;
  uint pad;
};

SHARED_END

SHARED_ASSERT_SIZE(AdaptiveQueueHeader, 48);
SHARED_ASSERT_SIZE(AdaptiveDecidePush, 112);

SHARED_BEGIN
// Texels per side of level `level` of a `pixels`-wide G-buffer.
SHARED_INLINE uint adaptiveLevelSize(uint pixels, uint level) {
  return (pixels + (1u << level) - 1u) >> level;
}
// The pixel a level-L texel is shaded at: its block's top-left corner (inside the G-buffer for
// every texel of adaptiveLevelSize).
SHARED_INLINE uvec2 adaptiveRepresentative(uvec2 texel, uint level) {
  return texel * (1u << level);
}
SHARED_END

#endif
