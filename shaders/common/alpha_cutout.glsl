// glTF alpha MASK, the rule engine/alpha_cutout.h states and its CPU side evaluates in the same
// fp32 order: no surface where baseColorFactor.a x alpha8 < alphaCutoff x 255, alpha8 the base
// colour layer's top-mip byte at the texel containing the coordinates' fraction (no filtering).
#ifndef COMMON_ALPHA_CUTOUT_GLSL
#define COMMON_ALPHA_CUTOUT_GLSL

// A vertex's base colour coordinates: KHR_texture_transform's rows (SceneMaterial).
vec2 cutoutCoordinates(vec4 rowU, vec4 rowV, vec2 uv) {
  precise float u = (rowU.x * uv.x + rowU.y * uv.y) + rowU.z;
  precise float v = (rowV.x * uv.x + rowV.y * uv.y) + rowV.z;
  return vec2(u, v);
}

// Whether the surface exists at base colour coordinates uv; layer -1: the factor alone.
// Non-finite coordinates keep the surface.
bool cutoutOpaque(sampler2DArray textures, int layer, float alphaFactor, float cutoff, vec2 uv) {
  if (!(cutoff > 0.0) || any(isnan(uv)) || any(isinf(uv))) return true;
  float alpha8 = 255.0;
  if (layer >= 0) {
    int size = textureSize(textures, 0).x;
    precise vec2 f = uv - floor(uv);
    ivec2 texel = min(ivec2(f * float(size)), ivec2(size - 1));
    // The unorm byte back from its float: exact after rounding.
    alpha8 = round(texelFetch(textures, ivec3(texel, layer), 0).a * 255.0);
  }
  precise float alpha = alpha8 * alphaFactor;
  precise float threshold = cutoff * 255.0;
  return alpha >= threshold;
}

#endif
