// The scaled dual-paraboloid environment map in fp32 (shared/environment.h for the layout; the
// double twin and the derivation are gi/src/reference/env_paraboloid.{h,cpp}). Both maps use
// (s, t) = 1/2 + (x, y) / (2 b (1 + z_m)), z_m = z in layer 0 and -z in layer 1, so the two
// maps meet along the rim without a mirror. r = 4 b^2 (1 + z_m)^2 is the solid angle per unit
// texture area: a texel of an S x S level holds r / S^2 steradians.
#ifndef SHADERS_COMMON_ENV_PARABOLOID_GLSL
#define SHADERS_COMMON_ENV_PARABOLOID_GLSL

const float kEnvParaboloidScale = ENV_PARABOLOID_SCALE;

// The layer of a unit direction's hemisphere: 0 for z >= 0, 1 for z < 0.
uint envParaboloidLayer(vec3 direction) {
  return direction.z >= 0.0 ? 0u : 1u;
}

// (s, t) of a unit direction in its own layer (inside the disc of radius 1 / (2 b)).
vec2 envParaboloidCoordinates(vec3 direction) {
  float mapZ = abs(direction.z);
  return vec2(0.5) + direction.xy / (2.0 * kEnvParaboloidScale * (1.0 + mapZ));
}

// The unit direction of (s, t) in `layer`, for any (s, t): the inverse stereographic projection
// of (u, v) = b (2 st - 1), (2 u, 2 v, 1 - rho^2) / (1 + rho^2).
vec3 envParaboloidDirection(vec2 st, uint layer) {
  vec2 uv = kEnvParaboloidScale * (2.0 * st - 1.0);
  float rho2 = dot(uv, uv);
  float inv = 1.0 / (1.0 + rho2);
  float mapZ = (1.0 - rho2) * inv;
  return vec3(2.0 * uv * inv, layer == 0u ? mapZ : -mapZ);
}

// r = 4 b^2 (1 + |z|)^2, steradians per unit texture area, at a direction of its own layer.
float envParaboloidSolidAnglePerArea(vec3 direction) {
  float onePlusZ = 1.0 + abs(direction.z);
  return 4.0 * kEnvParaboloidScale * kEnvParaboloidScale * onePlusZ * onePlusZ;
}

#endif
