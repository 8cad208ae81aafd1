#version 460
// Visibility buffer -> G-buffer. Per pixel: the triangle id from the visibility buffer, the
// camera ray through the pixel centre intersected with that triangle's plane for barycentrics
// (exact for any view, and for triangles the rasterizer clipped), attributes interpolated, and
// textures filtered with ray differentials (the rays of the next pixel right and down give
// the UV gradients, as hardware derivatives would).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/gbuffer.h"
#include "shared/raster.h"
#include "shared/scene_data.h"
#include "common/camera_ray.glsl"
#include "common/octahedral.glsl"

layout(local_size_x = GBUFFER_GROUP_X, local_size_y = GBUFFER_GROUP_Y) in;

layout(std430, binding = 0) readonly buffer Visibility { uint64_t visibility[]; };
layout(std430, binding = 1) readonly buffer Vertices { SceneVertex vertices[]; };
layout(std430, binding = 2) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 3) readonly buffer TriangleMaterials { uint triangleMaterial[]; };
layout(std430, binding = 4) readonly buffer Materials { SceneMaterial materials[]; };
layout(binding = 5) uniform sampler2DArray baseColorTextures;  // sRGB format: reads are linear
layout(binding = 6) uniform sampler2DArray metallicRoughnessTextures;
layout(binding = 7, r32f) uniform writeonly image2D outDepth;
layout(binding = 8, rg16_snorm) uniform writeonly image2D outNormal;
layout(binding = 9, rgba16f) uniform writeonly image2D outDiffuse;
layout(binding = 10, rgba16f) uniform writeonly image2D outSpecular;
layout(binding = 11, rgba16f) uniform writeonly image2D outEmission;
layout(push_constant) uniform Push { GBufferResolvePush pc; };

// Barycentrics (u, v) of the ray's hit with the plane of triangle (a, b, c): Moller-Trumbore
// without the inside test, so neighbouring-pixel rays extrapolate smoothly past the edges.
vec2 planeBarycentrics(vec3 origin, vec3 dir, vec3 a, vec3 b, vec3 c) {
  vec3 e1 = b - a, e2 = c - a;
  vec3 p = cross(dir, e2);
  float det = dot(e1, p);
  if (abs(det) < 1e-30) return vec2(1.0 / 3.0);  // ray parallel to the plane
  vec3 s = origin - a;
  vec3 q = cross(s, e1);
  return vec2(dot(s, p), dot(dir, q)) / det;
}

// KHR_texture_transform: the rows u, v of a 2 x 3 affine map (SceneMaterial); gradients take its
// linear part only.
vec2 transformUv(vec3 u, vec3 v, vec2 uv) {
  return vec2(dot(u, vec3(uv, 1.0)), dot(v, vec3(uv, 1.0)));
}
vec2 transformGradient(vec3 u, vec3 v, vec2 d) { return vec2(dot(u.xy, d), dot(v.xy, d)); }

// A tangent-space normal map's normal, as engine::perturbedNormal (gbuffer_reference.h)
// derives it: the triangle's own frame, T along dp/du made orthogonal to n, B = n x T (the
// image's up, against dp/dv: glTF's v runs down), negated where the coordinates are mirrored; n
// itself where they give no frame.
vec3 perturbedNormal(vec3 n, vec3 a, vec3 b, vec3 c, vec2 uvA, vec2 uvB, vec2 uvC, vec3 mapped) {
  vec3 e1 = b - a, e2 = c - a;
  vec2 d1 = uvB - uvA, d2 = uvC - uvA;
  float det = d1.x * d2.y - d2.x * d1.y;
  if (!(abs(det) > 0.0)) return n;
  vec3 dpdu = (e1 * d2.y - e2 * d1.y) / det, dpdv = (e2 * d1.x - e1 * d2.x) / det;
  vec3 t = dpdu - n * dot(n, dpdu);
  float len = length(t);
  if (!(len > 1e-6 * length(dpdu))) return n;
  vec3 tangent = t / len;
  vec3 bitangent = cross(n, tangent) * (dot(cross(dpdu, dpdv), n) < 0.0 ? 1.0 : -1.0);
  return normalize(tangent * mapped.x + bitangent * mapped.y + n * mapped.z);
}

vec2 rayBarycentrics(vec2 pixel, vec3 a, vec3 b, vec3 c) {
  vec3 origin, dir;
  cameraRay(pc.invViewProj, pixelToNdc(pixel, pc.viewport), origin, dir);
  return planeBarycentrics(origin, dir, a, b, c);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.viewport))) return;
  ivec2 coord = ivec2(pixel);
  uint64_t vis = visibility[pixel.y * pc.viewport.x + pixel.x];
  if (uint(vis >> 32) == RASTER_EMPTY_HI) {
    imageStore(outDepth, coord, vec4(1.0));
    imageStore(outNormal, coord, vec4(0.0));
    imageStore(outDiffuse, coord, vec4(0.0));
    imageStore(outSpecular, coord, vec4(0.0));
    imageStore(outEmission, coord, vec4(0.0));
    return;
  }
  float depth = uintBitsToFloat(uint(vis >> 32));
  uint tri = uint(vis & 0xFFFFFFFFul);

  // Members are read one by one, as in direct_light.comp, where copying whole structs out of a
  // buffer measured ~15 % slower on lavapipe (docs/performance.md).
  uint i0 = indices[3 * tri], i1 = indices[3 * tri + 1], i2 = indices[3 * tri + 2];
  vec4 pA = vertices[i0].positionU, pB = vertices[i1].positionU, pC = vertices[i2].positionU;
  vec4 nA = vertices[i0].normalV, nB = vertices[i1].normalV, nC = vertices[i2].normalV;
  vec3 a = pA.xyz, b = pB.xyz, c = pC.xyz;
  vec2 uvA = vec2(pA.w, nA.w), uvB = vec2(pB.w, nB.w), uvC = vec2(pC.w, nC.w);

  vec2 centre = vec2(pixel) + 0.5;
  vec3 origin, dir;
  cameraRay(pc.invViewProj, pixelToNdc(centre, pc.viewport), origin, dir);
  vec2 bc = planeBarycentrics(origin, dir, a, b, c);
  vec2 bcX = rayBarycentrics(centre + vec2(1.0, 0.0), a, b, c);
  vec2 bcY = rayBarycentrics(centre + vec2(0.0, 1.0), a, b, c);
  vec2 duvA = uvB - uvA, duvB = uvC - uvA;
  vec2 uv = uvA + bc.x * duvA + bc.y * duvB;
  vec2 uvDx = (bcX.x - bc.x) * duvA + (bcX.y - bc.y) * duvB;
  vec2 uvDy = (bcY.x - bc.x) * duvA + (bcY.y - bc.y) * duvB;

  vec3 normal = normalize(nA.xyz * (1.0 - bc.x - bc.y) + nB.xyz * bc.x + nC.xyz * bc.y);
  uint material = triangleMaterial[tri];
  // A host's material index past its buffer is never read: no normal map, no reflectance below.
  bool known = material < pc.materialCount;
  // The normal map perturbs the front's normal (a back face then shows its negation).
  int normalLayer = known ? materials[material].normalLayer : -1;
  if (normalLayer >= 0) {
    vec3 u = materials[material].normalUvU.xyz, v = materials[material].normalUvV.xyz;
    vec3 mapped = textureGrad(metallicRoughnessTextures,
                              vec3(transformUv(u, v, uv), float(normalLayer)),
                              transformGradient(u, v, uvDx), transformGradient(u, v, uvDy))
                      .rgb * 2.0 - 1.0;
    mapped.xy *= materials[material].normalScale;
    normal = perturbedNormal(normal, a, b, c, transformUv(u, v, uvA), transformUv(u, v, uvB),
                             transformUv(u, v, uvC), mapped);
  }
  // Two-sided shading: a surface seen from behind is lit as its front, so flip the normal
  // toward the viewer using the geometric normal (interpolated normals can disagree).
  bool back = dot(cross(b - a, c - a), dir) > 0.0;
  if (back) normal = -normal;

  // In a light's view the back of a single-sided surface is no surface (glTF doubleSided false):
  // it keeps its depth, so it shadows, and reflects nothing; so does an unknown material.
  if (!known || (back && pc.backFaces == 1u && materials[material].doubleSided == 0u)) {
    imageStore(outDepth, coord, vec4(depth));
    imageStore(outNormal, coord, vec4(octEncode(normal), 0.0, 0.0));
    imageStore(outDiffuse, coord, vec4(0.0, 0.0, 0.0, 1.0));
    imageStore(outSpecular, coord, vec4(0.0));
    imageStore(outEmission, coord, vec4(0.0));
    return;
  }
  vec4 base = materials[material].baseColorFactor;
  int baseLayer = materials[material].baseColorLayer;
  int mrLayer = materials[material].metallicRoughnessLayer;
  if (baseLayer >= 0) {
    vec3 u = materials[material].baseColorUvU.xyz, v = materials[material].baseColorUvV.xyz;
    base *= textureGrad(baseColorTextures, vec3(transformUv(u, v, uv), float(baseLayer)),
                        transformGradient(u, v, uvDx), transformGradient(u, v, uvDy));
  }
  float metallic = materials[material].metallic, roughness = materials[material].roughness;
  if (mrLayer >= 0) {
    vec3 u = materials[material].metallicRoughnessUvU.xyz;
    vec3 v = materials[material].metallicRoughnessUvV.xyz;
    vec4 mr = textureGrad(metallicRoughnessTextures,
                          vec3(transformUv(u, v, uv), float(mrLayer)),
                          transformGradient(u, v, uvDx), transformGradient(u, v, uvDy));
    roughness *= mr.g;  // glTF packing: G = roughness, B = metallic
    metallic *= mr.b;
  }
  metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
  vec3 diffuse = base.rgb * (1.0 - metallic);
  // glTF's dielectric F0 (IOR 1.5) and F90, scaled by KHR_materials_specular.
  vec4 specular = materials[material].specular;
  vec3 f0 = mix(min(vec3(0.04) * specular.rgb, vec3(1.0)) * specular.a, base.rgb, metallic);
  float f90 = mix(specular.a, 1.0, metallic);

  imageStore(outDepth, coord, vec4(depth));
  imageStore(outNormal, coord, vec4(octEncode(normal), 0.0, 0.0));
  imageStore(outDiffuse, coord, vec4(diffuse, roughness));
  imageStore(outSpecular, coord, vec4(f0, f90));
  vec3 emission = materials[material].emissive.rgb;
  int emissiveLayer = materials[material].emissiveLayer;
  if (emissiveLayer >= 0) {
    vec3 u = materials[material].emissiveUvU.xyz, v = materials[material].emissiveUvV.xyz;
    emission *= textureGrad(baseColorTextures, vec3(transformUv(u, v, uv), float(emissiveLayer)),
                            transformGradient(u, v, uvDx), transformGradient(u, v, uvDy))
                    .rgb;
  }
  imageStore(outEmission, coord, vec4(emission, 1.0));
}
