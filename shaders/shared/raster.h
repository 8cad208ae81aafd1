// The compute rasterizer's shared definitions (raster_setup.comp -> raster_triangles.comp).
// Screen coordinates are fixed point with RASTER_SUBPIXEL_BITS fractional bits, pixel centres
// at +0.5, y down (row 0 is the top of the image; NDC y = -1 is the top, as in Vulkan).
#ifndef SHADERS_SHARED_RASTER_H
#define SHADERS_SHARED_RASTER_H
#include "interop.h"

#define RASTER_GROUP_SIZE 64
#define RASTER_SUBPIXEL_BITS 8
#define RASTER_SUBPIXEL_SCALE 256.0
// Triangles are clipped to |x|, |y| <= RASTER_GUARD_BAND * w in clip space (plus the near plane
// z >= 0), which bounds fixed-point coordinates so that edge functions fit in int64:
// with RASTER_MAX_VIEWPORT 8192, |x| < 8.5 * 8192 * 256 < 2^25, products < 2^52.
#define RASTER_GUARD_BAND 16.0
#define RASTER_MAX_VIEWPORT 8192
// Clipping a triangle by 5 planes leaves at most 8 vertices, i.e. 6 fan triangles.
#define RASTER_MAX_CLIP_VERTICES 8
// An empty visibility-buffer texel: (depth bits << 32) | triangle id, all ones.
#define RASTER_EMPTY_HI 0xFFFFFFFFu

SHARED_BEGIN

// A screen-space triangle that survived clipping and culling, ready for coverage tests.
// Vertices are ordered so that the doubled signed area is positive.
struct RasterTriangle {
  ivec2 p0;  // fixed-point screen position
  ivec2 p1;
  ivec2 p2;
  uint bboxMin;  // pixel x | (y << 16), inclusive
  uint bboxMax;  // pixel x | (y << 16), inclusive
  float z0;      // NDC depth in [0, 1]
  float z1;
  float z2;
  uint triangleId;  // index of the source triangle in the scene
};

// Written by raster_setup, consumed by raster_triangles; groups* doubles as the indirect
// dispatch arguments of raster_triangles.
struct RasterCounters {
  uint triangleCount;  // entries appended to the RasterTriangle list
  uint groupsX;        // ceil(triangleCount / RASTER_GROUP_SIZE)
  uint groupsY;        // 1
  uint groupsZ;        // 1
  uint dropped;        // entries lost because the list was full (a bug if ever non-zero)
  uint pad0;
  uint pad1;
  uint pad2;
};

struct RasterSetupPush {
  mat4 viewProj;       // (world - origin) -> Vulkan clip space (depth range [0, 1])
  vec4 origin;         // xyz: the view's eye (engine::rasterTransform), w unused
  uvec2 viewport;      // pixels
  uint triangleCount;  // source triangles
  uint capacity;       // RasterTriangle entries available
};

struct RasterTrianglesPush {
  uvec2 viewport;
  uint capacity;
  uint pad;
};

SHARED_END

SHARED_ASSERT_SIZE(RasterTriangle, 48);
SHARED_ASSERT_OFFSET(RasterTriangle, bboxMin, 24);
SHARED_ASSERT_OFFSET(RasterTriangle, z0, 32);
SHARED_ASSERT_SIZE(RasterCounters, 32);
SHARED_ASSERT_SIZE(RasterSetupPush, 96);
SHARED_ASSERT_SIZE(RasterTrianglesPush, 16);
#endif
