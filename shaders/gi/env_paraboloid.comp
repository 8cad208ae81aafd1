#version 460
// Environment conversion (docs/techniques/environment.md, pass 1): an equirectangular RGBA32F
// image (y up, theta from +y, phi from +x towards +z, row 0 at the top) -> level 0 of both
// layers of the scaled dual-paraboloid map (shared/environment.h, common/env_paraboloid.glsl).
// Each texel is the mean of four bilinear equirect reads at the directions of the points
// (x + {1/4, 3/4}, y + {1/4, 3/4}) / S of the texel; texels outside a layer's disc get the
// directions of the other hemisphere, as the mapping gives them. The CPU twin is
// gi/src/reference/env_map_reference.cpp (envMapFromEquirect), summed in the same order.
#extension GL_GOOGLE_include_directive : require

#include "shared/environment.h"
#include "shared/env_map.h"
#include "common/env_paraboloid.glsl"

layout(local_size_x = ENV_CONVERT_GROUP_X, local_size_y = ENV_CONVERT_GROUP_Y) in;

// Read with texelFetch only (exact texels; the bilinear weights are computed here, in fp32,
// because a sampler's sub-texel precision may be as coarse as 4 bits and the wrap modes differ
// per axis).
layout(binding = 0) uniform sampler2D equirect;
layout(binding = 1, rgba32f) uniform writeonly image2DArray map;  // level 0, both layers
layout(push_constant) uniform Push { EnvConvertPush pc; };

const float kPi = 3.14159265358979;

// atan(t) for t in [0, 1], accurate to fp32 rounding on every driver (the built-in atan may be
// off by 4096 ulp in Vulkan, which would move a read by a quarter texel of a 1024-wide map).
// t > tan(pi/8) is reduced by atan(t) = pi/4 + atan((t - 1) / (t + 1)) to |t| <= 0.4142; there
// the Taylor series atan t = sum (-1)^k t^(2k+1) / (2k+1) up to t^23 leaves a truncation below
// 0.4142^25 / 25 = 1.1e-11.
float envAtanUnit(float t) {
  float offset = 0.0;
  if (t > 0.41421356) {
    t = (t - 1.0) / (t + 1.0);
    offset = 0.25 * kPi;
  }
  float t2 = t * t;
  float p = 1.0 / 23.0;
  for (int k = 10; k >= 0; --k) p = p * t2 + ((k & 1) == 0 ? 1.0 : -1.0) / float(2 * k + 1);
  return offset + t * p;
}

// atan2(y, x) in (-pi, pi]; (x, y) must not both be zero.
float envAtan2(float y, float x) {
  float ax = abs(x), ay = abs(y);
  float a = envAtanUnit(min(ax, ay) / max(ax, ay));
  if (ay > ax) a = 0.5 * kPi - a;
  if (x < 0.0) a = kPi - a;
  return y < 0.0 ? -a : a;
}

// (u, v) of a unit direction (gi::equirectFromDirection): u = phi / 2 pi in [0, 1), v = theta / pi.
// The sub-texel points never hit a pole exactly (s = 1/2 is never a sample position).
vec2 equirectFromDirection(vec3 d) {
  float theta = envAtan2(length(d.xz), d.y);
  float phi = envAtan2(d.z, d.x);
  if (phi < 0.0) phi += 2.0 * kPi;
  float u = phi / (2.0 * kPi);
  if (u >= 1.0) u = 0.0;
  return vec2(u, theta / kPi);
}

// Bilinear read with texel centres at (i + 1/2) / w: u wraps around, v is clamped to the first
// and last rows (gi::equirectBilinear). u in [0, 1) and v in [0, 1] keep the lower texel index
// in [-1, w - 1] and [-1, h - 1].
vec3 equirectBilinear(vec2 uv) {
  ivec2 size = ivec2(pc.equirectSize);
  vec2 p = uv * vec2(size) - 0.5;
  vec2 p0 = floor(p);
  vec2 f = p - p0;
  ivec2 i0 = ivec2(p0);
  int xa = i0.x < 0 ? size.x - 1 : i0.x;
  int xb = i0.x + 1 >= size.x ? 0 : i0.x + 1;
  int ya = max(i0.y, 0);
  int yb = min(i0.y + 1, size.y - 1);
  vec3 top = texelFetch(equirect, ivec2(xa, ya), 0).rgb * (1.0 - f.x) +
             texelFetch(equirect, ivec2(xb, ya), 0).rgb * f.x;
  vec3 bottom = texelFetch(equirect, ivec2(xa, yb), 0).rgb * (1.0 - f.x) +
                texelFetch(equirect, ivec2(xb, yb), 0).rgb * f.x;
  return top * (1.0 - f.y) + bottom * f.y;
}

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= pc.mapSize || id.y >= pc.mapSize || id.z >= 2u) return;
  float invSize = 1.0 / float(pc.mapSize);  // exact: the size is a power of two
  vec3 rows[2];
  for (int j = 0; j < 2; ++j) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 2; ++i) {
      vec2 st = (vec2(id.xy) + vec2(0.25 + 0.5 * float(i), 0.25 + 0.5 * float(j))) * invSize;
      sum += equirectBilinear(equirectFromDirection(envParaboloidDirection(st, id.z)));
    }
    rows[j] = sum;
  }
  imageStore(map, ivec3(id), vec4((rows[0] + rows[1]) * 0.25, 1.0));
}
