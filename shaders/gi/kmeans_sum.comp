#version 460
// k-means update (shaders/shared/kmeans.h), one work group per cluster: its members, contiguous
// after the sort, are summed by KMEANS_SUM_GROUP threads in strides and a fixed-order tree, so
// the sums are the same every run and a large cluster is not one thread's serial walk ([S3]'s
// "Sum" is linear in the cluster size). The six attribute sums become the VSGL through the
// filtered path's buildVsglLobe; the weighted mean feature becomes the new centre (kept when
// the members' weights sum to 0). CPU twin: gi::sumClustersReference.
#extension GL_GOOGLE_include_directive : require

#include "shared/vsgl.h"
#include "common/kmeans_texel.glsl"
#include "common/vsgl_lobes.glsl"

layout(local_size_x = KMEANS_SUM_GROUP) in;

layout(std430, binding = VSGL_ATTR_COUNT) buffer Centres { vec4 centres[]; };
layout(std430, binding = VSGL_ATTR_COUNT + 1) readonly buffer Values { uint values[]; };
layout(std430, binding = VSGL_ATTR_COUNT + 2) readonly buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = VSGL_ATTR_COUNT + 3) writeonly buffer Vsgls { Vsgl vsgls[]; };
layout(push_constant) uniform Push { KmeansPush pc; };

const uint kSums = VSGL_ATTR_COUNT + 1;  // the attributes, then (sum w f, sum w)
shared vec4 partial[kSums][KMEANS_SUM_GROUP];

void main() {
  uint k = gl_WorkGroupID.x, g = gl_LocalInvocationID.x;
  uvec2 range = ranges[k];
  vec4 sums[kSums];
  for (uint a = 0u; a < kSums; ++a) sums[a] = vec4(0.0);
  for (uint j = range.x + g; j < range.y; j += KMEANS_SUM_GROUP) {
    uint texel = values[j];
    ivec2 t = ivec2(texel % pc.size, texel / pc.size);
    vec4 texelSums[VSGL_ATTR_COUNT];
    texelSums[VSGL_ATTR_DIFFUSE_POWER] = texelFetch(diffusePower, t, 0);
    texelSums[VSGL_ATTR_DIFFUSE_POSITION] = texelFetch(diffusePosition, t, 0);
    texelSums[VSGL_ATTR_DIFFUSE_AXIS] = texelFetch(diffuseAxis, t, 0);
    texelSums[VSGL_ATTR_SPECULAR_POWER] = texelFetch(specularPower, t, 0);
    texelSums[VSGL_ATTR_SPECULAR_POSITION] = texelFetch(specularPosition, t, 0);
    texelSums[VSGL_ATTR_SPECULAR_AXIS] = texelFetch(specularAxis, t, 0);
    for (uint i = 0u; i < VSGL_ATTR_COUNT; ++i) sums[i] += texelSums[i];
    KmeansTexel m = kmeansTexelFrom(
        t, texelSums[VSGL_ATTR_DIFFUSE_POWER], texelSums[VSGL_ATTR_SPECULAR_POWER],
        texelSums[VSGL_ATTR_DIFFUSE_POSITION].xyz, texelSums[VSGL_ATTR_SPECULAR_POSITION].xyz,
        texelSums[VSGL_ATTR_DIFFUSE_AXIS].w, pc.size, pc.space, pc.weighting);
    sums[VSGL_ATTR_COUNT] += vec4(m.weight * m.feature, m.weight);
  }
  for (uint a = 0u; a < kSums; ++a) partial[a][g] = sums[a];
  barrier();
  for (uint offset = KMEANS_SUM_GROUP / 2u; offset > 0u; offset >>= 1u) {
    if (g < offset)
      for (uint a = 0u; a < kSums; ++a) partial[a][g] += partial[a][g + offset];
    barrier();
  }
  if (g != 0u) return;
  Vsgl v;
  v.diffuse = buildVsglLobe(partial[VSGL_ATTR_DIFFUSE_POWER][0],
                            partial[VSGL_ATTR_DIFFUSE_POSITION][0],
                            partial[VSGL_ATTR_DIFFUSE_AXIS][0], pc.origin.xyz);
  v.specular = buildVsglLobe(partial[VSGL_ATTR_SPECULAR_POWER][0],
                             partial[VSGL_ATTR_SPECULAR_POSITION][0],
                             partial[VSGL_ATTR_SPECULAR_AXIS][0], pc.origin.xyz);
  v.kernel = vec4(0.0, 0.0, -1.0, float(range.y - range.x));  // a cluster: no mip level
  v.visibilityPoint = vec4(0.0);  // the ISM from the lobes' mean
  vsgls[k] = v;
  vec4 weighted = partial[VSGL_ATTR_COUNT][0];
  if (weighted.w > 0.0) centres[k] = vec4(weighted.xyz / weighted.w, 0.0);
}
