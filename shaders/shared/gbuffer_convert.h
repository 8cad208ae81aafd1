// gbuffer_convert.comp: a host's depth and normal encodings (gi::DepthEncoding,
// gi::NormalEncoding) turned into the module's own (shared/gbuffer.h: forward Vulkan NDC depth in
// R32F, 1 = sky; octahedral normals in RG16 SNORM). The CPU twin is
// gi/src/reference/gbuffer_convert_reference.cpp.
#ifndef SHADERS_SHARED_GBUFFER_CONVERT_H
#define SHADERS_SHARED_GBUFFER_CONVERT_H
#include "interop.h"

#define GBUFFER_CONVERT_GROUP 8
// Depth encodings (gi::DepthEncoding).
// The result is forward NDC depth; outside [0, 1) (non-finite included) it is the sky's 1.
#define GBUFFER_DEPTH_NDC 0u           // forward NDC depth, 1 = sky (copied)
#define GBUFFER_DEPTH_REVERSED_NDC 1u  // reversed-Z NDC depth, 0 = sky: 1 - d
#define GBUFFER_DEPTH_VIEW_DISTANCE 2u // metres along the view axis, <= 0 or non-finite = sky
// Normal encodings (gi::NormalEncoding).
#define GBUFFER_NORMAL_OCTAHEDRAL 0u     // RG: octahedral (copied)
#define GBUFFER_NORMAL_WORLD_SIGNED 1u   // RGB: the world-space normal
#define GBUFFER_NORMAL_WORLD_UNSIGNED 2u // RGB: normal * 0.5 + 0.5

SHARED_BEGIN

struct GBufferConvertPush {
  // The forward projection's depth row: NDC z of view-space z is (a z + b) / (c z + d) with
  // (a, b, c, d) = (proj[2][2], proj[3][2], proj[2][3], proj[3][3]) (GBUFFER_DEPTH_VIEW_DISTANCE).
  vec4 depthRow;
  uvec2 viewport;
  uint depthEncoding;
  uint normalEncoding;
};

SHARED_END

SHARED_ASSERT_SIZE(GBufferConvertPush, 32);
#endif
