// An ISM frame (common/ism_lookup.glsl) broadcast from one lane of the subgroup, for the shading
// passes that load one VSGL per lane and loop over the block (vsgl_shade.comp, vpl_shade.comp).
// The includer enables GL_KHR_shader_subgroup_ballot and includes ism_lookup.glsl first.
#ifndef SHADERS_COMMON_ISM_BROADCAST_GLSL
#define SHADERS_COMMON_ISM_BROADCAST_GLSL

// Each broadcast scalar costs lavapipe about as much as ten arithmetic operations per lane (VSGL
// shading measured 7 % faster with the two tangents recomputed instead of broadcast), so only
// what cannot be recomputed travels: the centre, the axis, and the extent with `lit` folded into
// its sign (a lit frame's extent is a square root, >= 0). The recomputed tangents are those the
// lane computed, by the same function from the same axis.

// The frame of lane `lane` whose axis the caller already has (`axis`, equal to that lane's
// f.axis whenever its frame is lit; an unlit frame is never looked up).
IsmFrame broadcastFrame(IsmFrame f, vec3 axis, uint lane) {
  IsmFrame b;
  b.centre = subgroupBroadcast(f.centre, lane);
  float extent = subgroupBroadcast(f.lit ? f.extent : -1.0, lane);
  b.lit = extent >= 0.0;
  b.extent = max(extent, 0.0);
  b.axis = axis;
  ismFrameBasis(axis, b.tangent, b.bitangent);
  return b;
}

IsmFrame broadcastFrame(IsmFrame f, uint lane) {
  return broadcastFrame(f, subgroupBroadcast(f.axis, lane), lane);
}

#endif
