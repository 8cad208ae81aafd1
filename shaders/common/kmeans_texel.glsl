// One RSM texel as the k-means baseline sees it (shaders/shared/kmeans.h), from level 0 of the
// attribute pyramids (common/attribute_pyramids.glsl). CPU twin: gi::kmeansTexels.
#ifndef SHADERS_COMMON_KMEANS_TEXEL_GLSL
#define SHADERS_COMMON_KMEANS_TEXEL_GLSL

#include "shared/kmeans.h"
#include "common/attribute_pyramids.glsl"

struct KmeansTexel {
  vec3 feature;  // texel centre in [0, 1]^2 (image space) or VPL position - RSM origin (world)
  float weight;  // PDF or 1
  bool powered;  // carries power: belongs to a cluster
};

KmeansTexel kmeansTexel(uint index, uint size, uint space, uint weighting) {
  ivec2 t = ivec2(index % size, index / size);
  KmeansTexel k;
  float wd = texelFetch(diffusePower, t, 0).w;
  float ws = texelFetch(specularPower, t, 0).w;
  k.powered = wd + ws > 0.0;
  if (space == KMEANS_SPACE_IMAGE) {
    k.feature = vec3((vec2(t) + 0.5) / float(size), 0.0);
  } else {
    // Both position channels hold w y: their sum over w_d + w_s is y whichever lobe has power.
    vec3 sum = texelFetch(diffusePosition, t, 0).xyz +
               texelFetch(specularPosition, t, 0).xyz;
    k.feature = k.powered ? sum / (wd + ws) : vec3(0.0);
  }
  k.weight = !k.powered ? 0.0
           : weighting == KMEANS_WEIGHT_PDF ? texelFetch(diffuseAxis, t, 0).w
                                            : 1.0;
  return k;
}

#endif
