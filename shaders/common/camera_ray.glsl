// Rays through pixel positions from an inverse view-projection matrix. Works unchanged for
// perspective (also with an infinite far plane) and orthographic views: the ray runs from the
// near-plane point (NDC z = 0) through the point at NDC z = 0.5, which is finite in both.
#ifndef SHADERS_COMMON_CAMERA_RAY_GLSL
#define SHADERS_COMMON_CAMERA_RAY_GLSL

vec3 unproject(mat4 invViewProj, vec2 ndc, float z) {
  vec4 h = invViewProj * vec4(ndc, z, 1.0);
  return h.xyz / h.w;
}

// Pixel coordinates (x right, y down, pixel centres at +0.5) to Vulkan NDC.
vec2 pixelToNdc(vec2 pixel, uvec2 viewport) { return pixel / vec2(viewport) * 2.0 - 1.0; }

void cameraRay(mat4 invViewProj, vec2 ndc, out vec3 origin, out vec3 direction) {
  origin = unproject(invViewProj, ndc, 0.0);
  direction = normalize(unproject(invViewProj, ndc, 0.5) - origin);
}

#endif
