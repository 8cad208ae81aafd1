#version 460
// ISM build, step 3a (shaders/shared/ism.h): the pull half of pull-push hole filling (Ritschel
// et al. 2008, after Grossman and Dally 1998; vsgl-math.md section 8), over the atlas's mip
// levels (level l of a tile is its (S >> l)^2 block of mip l). One dispatch per level
// l = 1..log2 S, one thread per texel: the mean of the VALID texels among its 2 x 2 children at
// level l - 1 (valid: not ISM_EMPTY), ISM_EMPTY when none is. The children of a texel always
// lie in the same tile, so VSGLs' maps never mix. CPU twin: ismPullPushReference.
#extension GL_GOOGLE_include_directive : require

#include "shared/ism.h"

layout(local_size_x = ISM_IMAGE_GROUP, local_size_y = ISM_IMAGE_GROUP) in;

layout(binding = 0, r32ui) uniform readonly uimage2D finer;     // level l - 1
layout(binding = 1, r32ui) uniform writeonly uimage2D target;  // level l
layout(push_constant) uniform Push { IsmPullPushPush pc; };

void main() {
  uvec2 t = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(t, pc.size))) return;
  float sum = 0.0;
  float count = 0.0;
  for (uint c = 0u; c < 4u; ++c) {
    uint bits = imageLoad(finer, ivec2(2u * t + uvec2(c & 1u, c >> 1u))).r;
    bool valid = bits != ISM_EMPTY;
    sum += valid ? uintBitsToFloat(bits) : 0.0;
    count += valid ? 1.0 : 0.0;
  }
  imageStore(target, ivec2(t), uvec4(count > 0.0 ? floatBitsToUint(sum / count) : ISM_EMPTY));
}
