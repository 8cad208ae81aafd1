// The surface model of the G-buffer: Lambert diffuse plus GGX microfacet specular with the
// height-correlated Smith visibility (Heitz 2014, Eq. 99) and Schlick's Fresnel, as glTF's
// metallic-roughness model specifies (alpha = r^2), with F90 for KHR_materials_specular.
#ifndef SHADERS_COMMON_BRDF_GLSL
#define SHADERS_COMMON_BRDF_GLSL

const float kPi = 3.14159265358979;
// alpha below this underflows alpha^4 in fp32; mirror-like surfaces are clamped to it.
const float kMinAlpha = 1e-3;

// GGX NDF. The usual denominator nh^2 (a2 - 1) + 1 cancels catastrophically near the peak of a
// sharp lobe (a2 << 1, nh -> 1); 1 - nh^2 = |n x h|^2 gives the same value without cancellation.
float ggxD(vec3 n, vec3 h, float a2) {
  float nh = max(dot(n, h), 0.0);
  vec3 nxh = cross(n, h);
  float d = nh * nh * a2 + dot(nxh, nxh);
  return a2 / (kPi * d * d);
}

// V = G2 / (4 |n.l| |n.v|), height-correlated Smith for GGX.
float smithGgxCorrelatedV(float nv, float nl, float a2) {
  float gv = nl * sqrt(nv * nv * (1.0 - a2) + a2);
  float gl = nv * sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / max(gv + gl, 1e-12);
}

vec3 schlickFresnel(vec3 f0, float f90, float vh) {
  float m = 1.0 - vh;
  float m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

// BRDF times cosine for unit n, v (to viewer), l (to light).
vec3 brdfCos(vec3 n, vec3 v, vec3 l, vec3 diffuse, vec3 f0, float f90, float roughness) {
  float nl = dot(n, l);
  // Interpolated normals can face slightly away from the viewer; keep such pixels lit.
  float nv = max(dot(n, v), 1e-4);
  if (nl <= 0.0) return vec3(0.0);
  float alpha = max(roughness * roughness, kMinAlpha);
  float a2 = alpha * alpha;
  vec3 h = normalize(v + l);
  vec3 spec = ggxD(n, h, a2) * smithGgxCorrelatedV(nv, nl, a2) * schlickFresnel(f0, f90, max(dot(v, h), 0.0));
  return (diffuse / kPi + spec) * nl;
}

#endif
