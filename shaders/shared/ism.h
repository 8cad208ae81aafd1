// Imperfect shadow maps for VSGLs (Ritschel et al. 2008, vsgl-math.md section 8; the design,
// dispatch sizes and measurements are in docs/techniques/ism.md). The passes:
//
//   points (once per scene, recordPoints):
//     ism_area.comp       per triangle: its area (m^2) into the CDF buffer
//     ism_scan.comp       one work group: deterministic inclusive prefix sum of the areas in
//                         place (each thread sums a contiguous chunk in order, a fixed
//                         shared-memory scan joins the chunks), so CDF[t] = area of triangles <= t
//     ism_points.comp     per pool point i: stratified u_i = (i + 0.5) / P mapped through the
//                         CDF by binary search, barycentrics from the R2 sequence (fixed-point
//                         golden ratios, exact) and the square-to-triangle warp
//   build (every frame, recordBuild):
//     ism_positions.comp  world positions of the pool points the VSGLs use, from the CURRENT
//                         vertex buffer (points follow moving geometry), into an image
//     ism_splat.comp      one work group per VSGL: its subset of points projected into its
//                         paraboloid tile, nearest distance kept with a 32-bit atomicMin
//     ism_pull.comp       pull-push hole filling inside each tile over the atlas's mip levels:
//     ism_push.comp       one dispatch per level and direction
//   lookup (common/ism_lookup.glsl, and ism_visibility.comp, the one-VSGL debug view).
//
// Atlas: one R32_UINT image of tiles, S x S texels each, 2^tilesPerRowLog2 tiles per row
// (1024 VSGLs x 64^2: a 2048^2 atlas of 32 x 32 tiles, as in [S3]); tile k at column
// k mod tilesPerRow, row k / tilesPerRow. A texel holds the distance (metres, fp32 bits) from
// the VSGL's ISM centre to the nearest splatted point: uint order is float order for
// non-negative floats, so atomicMin on the bits keeps the nearest. ISM_EMPTY marks texels no
// point reached. After pull-push every texel is a finite distance, or +inf in a tile that
// received no point at all (nothing occludes). Mip level l of the same image is pull-push
// level l: tiles stay S >> l apart, so a 2 x 2 reduction never mixes two VSGLs' tiles.
//
// Subsets: with pool size P and M points per VSGL (both powers of two), the stride is s = P / M
// and VSGL k uses the points o_k + j s, j < M, o_k = ISM_SUBSET_OFFSET(k, s). Because the pool
// is stratified along the area CDF, every subset is itself a stratified, area-proportional set
// of M points; s different VSGLs get disjoint subsets (beyond s they repeat).
#ifndef SHADERS_SHARED_ISM_H
#define SHADERS_SHARED_ISM_H
#include "interop.h"

#define ISM_GROUP_SIZE 64   // threads per group of the per-triangle/per-point/per-VSGL passes
#define ISM_SCAN_GROUP 256  // threads of the single scan work group
#define ISM_IMAGE_GROUP 8   // 8 x 8 threads per group of the image passes
// Point i's position lives at texel (i mod ISM_POSITIONS_WIDTH, i / ISM_POSITIONS_WIDTH) of the
// positions image (RGBA32F, P / ISM_POSITIONS_WIDTH rows).
#define ISM_POSITIONS_WIDTH 1024u
#define ISM_POSITIONS_SHIFT 10u
// A texel no point reached (the uint bits of a NaN: above every non-negative float's bits).
#define ISM_EMPTY 0xFFFFFFFFu
#define ISM_INFINITY 0x7F800000u  // +inf: a texel of a tile without any point
// A pool point that lies on no surface (the scene has no area, or an alpha test cut the point):
// skipped by the splat.
#define ISM_NO_TRIANGLE 0xFFFFFFFFu
// R2 sequence (Roberts 2018): frac(1/2 + i / phi2^k), phi2 = 1.3247179572 (the plastic number),
// as 32-bit fixed point so that i * a wraps exactly in uint arithmetic: round(2^32 / phi2) and
// round(2^32 / phi2^2).
#define ISM_R2_A1 3242174889u
#define ISM_R2_A2 2447445414u
// Subset offset of VSGL k for stride s (a power of two): an odd multiplier permutes k mod s, so
// neighbouring VSGLs (often neighbours on the RSM) take subsets far apart in the pool.
#define ISM_SUBSET_MULTIPLIER 0x9E3779B1u
#define ISM_SUBSET_OFFSET(k, stride) (((k)*ISM_SUBSET_MULTIPLIER) & ((stride)-1u))
// Lookup: the slope term uses tan of the receiver's angle to the VSGL, clamped here (grazing
// receivers would otherwise get an unbounded bias).
#define ISM_MAX_SLOPE 8.0
// Percentage-closer filters (IsmParams::pcf).
#define ISM_PCF_NEAREST 0u   // the texel the receiver projects into
#define ISM_PCF_BILINEAR 1u  // 2 x 2 texels, bilinear weights of the depth-test results
#define ISM_PCF_BOX3 2u      // 3 x 3 texels around the nearest, equal weights
#define ISM_MAX_PCF ISM_PCF_BOX3

SHARED_BEGIN

// One pool point: a triangle and the barycentric weights of its vertices 1 and 2 as
// packUnorm2x16 (1/65535 of an edge: 0.15 mm on a 10 m triangle).
struct IsmPoint {
  uint triangle;  // ISM_NO_TRIANGLE when the scene has no area or the point is cut out
  uint bary;      // unorm16 x 2: (b1, b2); b0 = 1 - b1 - b2
};

// What a lookup needs besides the atlas: a shading pass embeds it in its push constants
// (Ism::params() on the host).
struct IsmParams {
  uint mapSize;          // S, texels per tile side
  uint tilesPerRowLog2;  // log2 of the atlas's tiles per row
  uint pcf;              // ISM_PCF_*
  float depthBias;       // metres subtracted from the receiver's distance
  float slopeBias;       // texel footprints (distance x texel angle) x tan(receiver angle)
  float centreOffset;    // metres the ISM centre sits above the VSGL mean along its axis
  uint pad0;
  uint pad1;
};

struct IsmAreaPush {
  uint triangleCount;
  uint vertexCount;  // a triangle naming a vertex at or past it gets no area (no points)
  uint pad1;
  uint pad2;
};

struct IsmPointsPush {
  uint triangleCount;
  uint pointCount;     // P
  uint materialCount;  // a material index at or past it is not alpha-tested
  uint pad1;
};

struct IsmPositionsPush {
  uint pointsPerVsgl;  // M
  uint stride;         // s = P / M
  uint classCount;     // min(V, s): subsets in use
  uint pad0;
};

struct IsmSplatPush {
  IsmParams params;
  uint pointsPerVsgl;  // M
  uint stride;         // s
  uint pad0;
  uint pad1;
};

struct IsmPullPushPush {
  uvec2 size;      // texels of the atlas level written (the rows of tiles in use)
  uint tileShift;  // log2 of a tile's side at that level
  uint level;      // the level written: pull 1..log2 S, push log2 S - 1..0
};

struct IsmVisibilityPush {
  mat4 invViewProj;
  uvec2 viewport;
  uint vsglIndex;
  uint pad0;
  IsmParams params;
};

SHARED_END

SHARED_ASSERT_SIZE(IsmPoint, 8);
SHARED_ASSERT_SIZE(IsmParams, 32);
SHARED_ASSERT_SIZE(IsmAreaPush, 16);
SHARED_ASSERT_SIZE(IsmPointsPush, 16);
SHARED_ASSERT_SIZE(IsmPositionsPush, 16);
SHARED_ASSERT_SIZE(IsmSplatPush, 48);
SHARED_ASSERT_OFFSET(IsmSplatPush, pointsPerVsgl, 32);
SHARED_ASSERT_SIZE(IsmPullPushPush, 16);
SHARED_ASSERT_SIZE(IsmVisibilityPush, 112);
SHARED_ASSERT_OFFSET(IsmVisibilityPush, params, 80);
#endif
