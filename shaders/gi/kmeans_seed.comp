#version 460
// k-means, fresh centres (shaders/shared/kmeans.h): PDF-proportional and stratified. Centre i is
// the feature of the texel that lattice point i of N lands in when warped down the PDF pyramid,
// the filtered path's own sampling; an all-zero PDF puts every centre at 0. CPU twin:
// gi::kmeansSeeds.
#extension GL_GOOGLE_include_directive : require

#include "common/kmeans_texel.glsl"
#include "common/lattice_warp.glsl"

layout(local_size_x = KMEANS_SEED_GROUP) in;

layout(std430, binding = VSGL_ATTR_COUNT) writeonly buffer Centres { vec4 centres[]; };
layout(push_constant) uniform Push { KmeansPush pc; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.clusters) return;
  if (!(pdfTexel(ivec2(0), int(pc.topLevel)) > 0.0)) {
    centres[i] = vec4(0.0);
    return;
  }
  vec2 u = fibonacciPoint(i, pc.clusters);
  ivec2 t = warpToTexel(u, int(pc.topLevel));
  uint texel = uint(t.y) * pc.size + uint(t.x);
  centres[i] = vec4(kmeansTexel(texel, pc.size, pc.space, pc.weighting).feature, 0.0);
}
