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

// From the texel's already fetched power and position sums and PDF (kmeans_sum reads them for
// its sums anyway).
KmeansTexel kmeansTexelFrom(ivec2 t, vec4 diffuse, vec4 specular, vec3 diffuseSum,
                            vec3 specularSum, float pdf, uint size, uint space, uint weighting) {
  KmeansTexel k;
  float w = diffuse.w + specular.w;
  k.powered = w > 0.0;
  // Both position channels hold w y: their sum over w_d + w_s is y whichever lobe has power.
  k.feature = space == KMEANS_SPACE_IMAGE ? vec3((vec2(t) + 0.5) / float(size), 0.0)
            : k.powered                   ? (diffuseSum + specularSum) / w
                                          : vec3(0.0);
  k.weight = !k.powered ? 0.0 : weighting == KMEANS_WEIGHT_PDF ? pdf : 1.0;
  return k;
}

KmeansTexel kmeansTexel(uint index, uint size, uint space, uint weighting) {
  ivec2 t = ivec2(index % size, index / size);
  return kmeansTexelFrom(t, texelFetch(diffusePower, t, 0), texelFetch(specularPower, t, 0),
                         texelFetch(diffusePosition, t, 0).xyz,
                         texelFetch(specularPosition, t, 0).xyz,
                         texelFetch(diffuseAxis, t, 0).w, size, space, weighting);
}

#endif
