// Direct lighting of the G-buffer by the scene's punctual lights with shadow maps rendered by
// the compute rasterizer (one visibility buffer per shadow view, depth in the high 32 bits).
#ifndef SHADERS_SHARED_DIRECT_LIGHT_H
#define SHADERS_SHARED_DIRECT_LIGHT_H
#include "interop.h"

#define DIRECT_GROUP_X 8
#define DIRECT_GROUP_Y 8
// Lights and shadow views live in uniform buffers: lavapipe reads a uniform-indexed UBO once per
// SIMD row but gathers storage-buffer structs lane by lane. 256 * 80 bytes stays under the
// 64 KiB uniform range that Vulkan devices commonly offer.
#define DIRECT_MAX_LIGHTS 256
#define DIRECT_MAX_SHADOW_VIEWS 256
#define LIGHT_DIRECTIONAL 0u
#define LIGHT_POINT 1u
#define LIGHT_SPOT 2u
// Normal-offset shadow bias, in shadow-map texels at the receiver. Moving the receiver by d along
// its normal gains d / cos(theta) of depth margin against its own surface (theta = angle to the
// light); the 3x3 PCF tap one texel up the slope plus half a texel of quantisation at each end
// costs 2 texel tan(theta). So d >= 2 sin(theta) texels suffices at every angle; 2.5 adds slack.
#define SHADOW_NORMAL_OFFSET_TEXELS 2.5

SHARED_BEGIN

// KHR_lights_punctual light with radiometric units: intensity in W/sr (point, spot) or W/m^2
// (directional), spot falloff as the extension's reference implementation.
struct GpuLight {
  vec4 position;   // xyz world position (point, spot)
  vec4 direction;  // xyz unit direction the light travels (spot, directional)
  vec4 radiance;   // rgb = colour * intensity, w = range in metres (0 = infinite)
  vec4 spot;       // x = angle scale 1/max(1e-3, cos inner - cos outer), y = -cos outer * x
  uvec4 info;      // x = LIGHT_*, y = first shadow view, z = shadow view count (0 = none), w = 0
};

// One shadow map: a view of the rasterizer. Point lights (and spots wider than a perspective
// view can hold) use 6 cube-face views ordered +X, -X, +Y, -Y, +Z, -Z.
struct ShadowView {
  mat4 viewProj;
  vec4 texel;  // world size of one texel: x * distance-to-light + y (x: perspective, y: ortho)
};

struct DirectLightPush {
  mat4 invViewProj;  // camera
  uvec2 viewport;
  uint lightCount;
  uint shadowResolution;  // shadow maps are square, this many texels on a side
};

SHARED_END

SHARED_ASSERT_SIZE(GpuLight, 80);
SHARED_ASSERT_SIZE(ShadowView, 80);
SHARED_ASSERT_SIZE(DirectLightPush, 80);
#endif
