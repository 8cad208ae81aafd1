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
// The coverage pass gives each work group at most this many of the pixels in the boxes of its
// RASTER_GROUP_SIZE triangles (a second dispatch dimension covers the rest,
// RasterCounters::groupsY; a group's boxes sum to less than 2^32 unless all 64 of its triangles
// fill an 8192^2 view). Besides
// spreading large triangles over many work groups, this bounds the loop iterations of one
// invocation: lavapipe (llvmpipe) silently ends a shader's loops once one invocation has run
// 65 535 iterations of them in total, and a thread walks 2^17 / 64 = 2 048 pixels here, about 8
// iterations each (the pixel loop and its binary search), ~16 000 in all. Without the bound a
// group of large triangles lost most of its pixels: a 512^2 shadow map of two 4 m quads 2 m
// below a spot showed the floor behind them instead.
#define RASTER_CHUNK_PIXELS 131072u
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
// dispatch arguments of raster_triangles, clipGroups* as those of raster_setup's clip pass and
// clusterCount, clusterGroups* as those of raster_setup itself (raster_cull writes them).
struct RasterCounters {
  uint triangleCount;   // entries appended to the RasterTriangle list
  uint groupsX;         // ceil(triangleCount / RASTER_GROUP_SIZE)
  uint groupsY;         // the largest group's pixel-box area / RASTER_CHUNK_PIXELS, rounded up
  uint groupsZ;         // 1
  uint clipCount;       // triangles listed for clipping (near plane or guard band crossed)
  uint clipGroupsX;     // ceil(clipCount / RASTER_GROUP_SIZE)
  uint clipGroupsY;     // 1
  uint clipGroupsZ;     // 1
  uint clusterCount;    // clusters kept by raster_cull, one setup work group each
  uint clusterGroupsY;  // 1
  uint clusterGroupsZ;  // 1
  uint dropped;         // entries lost because the list was full (a bug if ever non-zero)
};

// A cluster: RASTER_GROUP_SIZE consecutive scene triangles (the last one may hold fewer), so
// triangle ids stay those of the scene. raster_cull skips a cluster whose box lies outside
// the view before setup reads its vertices (engine/raster_clusters.h).
struct RasterCluster {
  vec4 boundsMin;  // xyz: the smallest coordinates of its triangles' vertices; w = 1: never
                   // culled (a position is not finite); min > max: no triangle to draw
  vec4 boundsMax;  // xyz: the largest; w unused
};

struct RasterBoundsPush {
  uint triangleCount;  // source triangles
  uint vertexCount;    // a triangle naming a vertex at or past it is left out
  uint pad0;
  uint pad1;
};

struct RasterSetupPush {
  mat4 viewProj;       // (world - origin) -> Vulkan clip space (depth range [0, 1])
  vec4 origin;         // xyz: the view's eye (engine::rasterTransform), w unused
  uvec2 viewport;      // pixels
  uint triangleCount;  // source triangles
  uint capacity;       // RasterTriangle entries available
  uint vertexCount;    // a triangle naming a vertex at or past it is left out
  uint cullClusters;   // 1: raster_cull skips clusters outside the view; 0: it keeps all
  uint pad0;
  uint pad1;
};

struct RasterTrianglesPush {
  mat4 viewProj;  // RasterSetupPush's transform: the alpha test's barycentrics
  vec4 origin;
  uvec2 viewport;
  uint capacity;
  uint materialCount;  // a material index at or past it is not alpha-tested
};

SHARED_END

SHARED_ASSERT_SIZE(RasterTriangle, 48);
SHARED_ASSERT_OFFSET(RasterTriangle, bboxMin, 24);
SHARED_ASSERT_OFFSET(RasterTriangle, z0, 32);
SHARED_ASSERT_SIZE(RasterCounters, 48);
SHARED_ASSERT_SIZE(RasterCluster, 32);
SHARED_ASSERT_SIZE(RasterBoundsPush, 16);
SHARED_ASSERT_SIZE(RasterSetupPush, 112);
SHARED_ASSERT_SIZE(RasterTrianglesPush, 96);
#endif
