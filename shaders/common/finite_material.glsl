// The rule for NaN and Inf in a host's G-buffer material channels (a broken texture; vsgl-math.md
// section 12, case 14), shared by every pass that reads them: a non-finite channel reads as the
// fallback (0 for albedo, F0 and F90; 1 for roughness), so that the pixel still gets finite light.
#ifndef SHADERS_COMMON_FINITE_MATERIAL_GLSL
#define SHADERS_COMMON_FINITE_MATERIAL_GLSL

const float kMaterialFltMax = 3.402823466e38;

// (A NaN fails every comparison, so |x| <= FLT_MAX holds exactly for the finite values.)
vec4 finiteOr(vec4 v, vec4 fallback) {
  return mix(fallback, v, lessThanEqual(abs(v), vec4(kMaterialFltMax)));
}
vec3 finiteOr(vec3 v, vec3 fallback) {
  return mix(fallback, v, lessThanEqual(abs(v), vec3(kMaterialFltMax)));
}

#endif
