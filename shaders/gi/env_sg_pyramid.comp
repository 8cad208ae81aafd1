#version 460
// Level 0 of the SG-light attribute pyramids (shared/env_sg.h) from level 0 of the converted
// environment (shared/environment.h), both layers per dispatch (z = layer). The mips are then
// env_mip_reduce.comp's exact box means. Per texel: its solid angle w inside its own
// hemisphere, its whole solid angle w_full and the integral of the direction over the whole
// texel (the other hemisphere's part included: real directions), by the midpoint rule on
// ENV_SG_TEXEL_SAMPLES^2 points (the points of env_sh.comp), then the texel's radiance and
// luminance times them. CPU twin: gi::envSgPyramids (gi/src/reference/env_sg_reference.cpp).
#extension GL_GOOGLE_include_directive : require

#include "shared/environment.h"
#include "shared/env_sg.h"
#include "common/env_paraboloid.glsl"

layout(local_size_x = ENV_SG_PYRAMID_GROUP_X, local_size_y = ENV_SG_PYRAMID_GROUP_Y) in;

layout(binding = 0, rgba32f) uniform readonly image2DArray map;  // level 0
layout(binding = 1, rgba32f) uniform writeonly image2DArray radianceOut;
layout(binding = 2, rgba32f) uniform writeonly image2DArray directionOut;
layout(push_constant) uniform Push { EnvSgPyramidPush pc; };

// Rec. 709 / sRGB primaries' luminance weights.
const vec3 kLuminance = vec3(0.2126, 0.7152, 0.0722);

void main() {
  uvec3 id = gl_GlobalInvocationID;
  uint n = pc.size;
  if (any(greaterThanEqual(id.xy, uvec2(n))) || id.z >= 2u) return;
  uint layer = id.z;
  const uint K = ENV_SG_TEXEL_SAMPLES;
  float invKn = 1.0 / float(K * n);  // exact: K n is a power of two
  float solidAngle = 0.0;      // the part in the own hemisphere
  float fullSolidAngle = 0.0;  // the whole texel
  vec3 direction = vec3(0.0);  // integral of the direction over the whole texel
  for (uint j = 0u; j < K; ++j)
    for (uint i = 0u; i < K; ++i) {
      // 2 st - 1 = (2 (K x + i) + 1 - K n) / (K n), exact; rho^2 never ties 1 (see the twin).
      vec2 c = vec2(2.0 * float(K * id.x + i) + 1.0 - float(K * n),
                    2.0 * float(K * id.y + j) + 1.0 - float(K * n)) * invKn;
      float rho2 = kEnvParaboloidScale * kEnvParaboloidScale * dot(c, c);
      float onePlusRho2 = 1.0 + rho2;
      float r = 16.0 * kEnvParaboloidScale * kEnvParaboloidScale / (onePlusRho2 * onePlusRho2);
      fullSolidAngle += r;
      direction += r * envParaboloidDirection(0.5 + 0.5 * c, layer);
      if (layer == 0u ? rho2 > 1.0 : rho2 >= 1.0) continue;  // the other hemisphere's point
      solidAngle += r;
    }
  solidAngle *= invKn * invKn;
  fullSolidAngle *= invKn * invKn;
  direction *= invKn * invKn;
  vec3 radiance = imageLoad(map, ivec3(id)).rgb;
  float luminance = dot(kLuminance, radiance);
  imageStore(radianceOut, ivec3(id), vec4(fullSolidAngle * radiance, solidAngle * luminance));
  imageStore(directionOut, ivec3(id), vec4(luminance * direction, fullSolidAngle * luminance));
}
