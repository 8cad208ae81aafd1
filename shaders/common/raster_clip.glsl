// The compute rasterizer's transform to clip space (engine::RasterTransform), shared by its setup
// and coverage passes. Relative to the eye first: p - origin is exact when the two are close
// (Sterbenz), so a scene far from the world origin keeps its depth order
// (docs/techniques/stability.md, case 6). `precise` and the explicit order make the CPU twin
// (raster_reference.cpp) round identically.
#ifndef COMMON_RASTER_CLIP_GLSL
#define COMMON_RASTER_CLIP_GLSL

vec4 rasterClip(mat4 viewProj, vec3 origin, vec3 world) {
  precise vec3 p = world - origin;
  precise vec4 c = viewProj[0] * p.x + viewProj[1] * p.y + viewProj[2] * p.z;
  precise vec4 r = c + viewProj[3];
  return r;
}

#endif
