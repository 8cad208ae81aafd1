// An ISM frame (common/ism_lookup.glsl) broadcast from one lane of the subgroup, for the shading
// passes that load one VSGL per lane and loop over the block (vsgl_shade.comp, vpl_shade.comp).
// The includer enables GL_KHR_shader_subgroup_ballot and includes ism_lookup.glsl first.
#ifndef SHADERS_COMMON_ISM_BROADCAST_GLSL
#define SHADERS_COMMON_ISM_BROADCAST_GLSL

IsmFrame broadcastFrame(IsmFrame f, uint lane) {
  IsmFrame b;
  b.centre = subgroupBroadcast(f.centre, lane);
  b.tangent = subgroupBroadcast(f.tangent, lane);
  b.bitangent = subgroupBroadcast(f.bitangent, lane);
  b.axis = subgroupBroadcast(f.axis, lane);
  b.lit = subgroupBroadcast(f.lit, lane);
  b.extent = subgroupBroadcast(f.extent, lane);
  return b;
}

#endif
