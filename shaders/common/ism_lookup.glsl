// Imperfect shadow maps (shaders/shared/ism.h, docs/techniques/ism.md): the ISM frame of a VSGL,
// the paraboloid projection, and the visibility lookup a shading pass calls per VSGL.
//
// For the lookup, the includer declares the atlas BEFORE including this file, under this name:
//   layout(binding = N, r32ui) uniform readonly uimage2D ismAtlas;
// (level 0 of Ism::atlas() on the host, in GENERAL layout: engine::Binding::storageImage(
// ism.atlas(), 0); any binding number), and passes an IsmParams (Ism::params(), e.g. embedded
// in its push constants). A shader that needs only the frame, the tile origin and the
// projection (the splat) defines ISM_FRAME_ONLY before including and declares no atlas.
#ifndef SHADERS_COMMON_ISM_LOOKUP_GLSL
#define SHADERS_COMMON_ISM_LOOKUP_GLSL
// The includer may fix the PCF mode at compile time by defining ISM_LOOKUP_PCF (for example as a
// specialization constant); otherwise ismVisibility reads it from its IsmParams.
#ifndef ISM_LOOKUP_PCF
#define ISM_LOOKUP_PCF params.pcf
#endif

#include "shared/ism.h"
#include "shared/vsgl.h"

// The frame a VSGL's map is rendered in: the hemisphere around `axis`, seen from `centre`.
struct IsmFrame {
  vec3 centre;     // world; the power-weighted lobe mean lifted by the centre offset
  vec3 tangent;    // paraboloid u direction
  vec3 bitangent;  // paraboloid v direction
  vec3 axis;       // hemisphere axis (unit)
  bool lit;        // false: the VSGL has no power, its map is empty and never consulted
  float extent;    // m: the VSGL's spatial standard deviation (lookups behind the base plane)
};

// The paraboloid's tangents around a unit axis (Duff et al. 2017, "Building an orthonormal
// basis, revisited"): continuous except across axis.z = 0, no normalisation.
void ismFrameBasis(vec3 axis, out vec3 tangent, out vec3 bitangent) {
  float s = axis.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + axis.z);
  float b = axis.x * axis.y * a;
  tangent = vec3(1.0 + s * axis.x * axis.x * a, s * b, -s * axis.x);
  bitangent = vec3(b, s + axis.y * axis.y * a, -axis.y);
}

// The ISM frame from a VSGL's two lobes: centre = mean of the lobe means weighted by their
// powers (power.a), extent = the square root of their variances weighted the same way, axis =
// the diffuse lobe's axis (the specular one when the diffuse lobe has no power), tangents from
// ismFrameBasis. The centre is lifted by
// `centreOffset` metres along the axis so that the VSGL's own surface (which passes through the
// mean on a flat receiver) falls below the hemisphere instead of occluding it.
IsmFrame ismFrameFromLobes(vec4 diffuseMeanVariance, vec3 diffuseAxis, float diffuseWeight,
                           vec4 specularMeanVariance, vec3 specularAxis, float specularWeight,
                           float centreOffset) {
  IsmFrame f;
  float weight = diffuseWeight + specularWeight;
  f.lit = weight > 0.0;
  vec3 diffuseMean = diffuseMeanVariance.xyz, specularMean = specularMeanVariance.xyz;
  f.extent = f.lit ? sqrt(max((diffuseWeight * diffuseMeanVariance.w +
                               specularWeight * specularMeanVariance.w) / weight, 0.0))
                   : 0.0;
  vec3 axis = diffuseWeight > 0.0 ? diffuseAxis : specularAxis;
  f.axis = axis;
  f.centre = f.lit ? (diffuseWeight * diffuseMean + specularWeight * specularMean) / weight +
                         centreOffset * axis
                   : vec3(0.0);
  ismFrameBasis(axis, f.tangent, f.bitangent);
  return f;
}

// The frame of a VSGL: its lobes' frame, centred on its visibility point when it has one
// (Vsgl::visibilityPoint), lifted the same way.
IsmFrame ismFrame(Vsgl vsgl, float centreOffset) {
  IsmFrame f = ismFrameFromLobes(vsgl.diffuse.meanVariance, vsgl.diffuse.axisSharpness.xyz,
                                 vsgl.diffuse.power.a, vsgl.specular.meanVariance,
                                 vsgl.specular.axisSharpness.xyz, vsgl.specular.power.a,
                                 centreOffset);
  if (f.lit && vsgl.visibilityPoint.w > 0.0)
    f.centre = vsgl.visibilityPoint.xyz + centreOffset * f.axis;
  return f;
}

// Paraboloid coordinates in [0, 1]^2 of the offset d = p - centre (|d| = dist > 0) whose
// component along the axis is along > 0: (u, v) = 1/2 + 1/2 (d_x, d_y) / (1 + d_z) for the unit
// direction, here with d unnormalised (one division). Conformal: one texel spans an angle of
// 2 (1 + d_z) / S radians in every direction (4/S at the pole, 2/S at the rim).
vec2 ismParaboloid(IsmFrame f, vec3 d, float dist, float along) {
  return 0.5 + 0.5 * vec2(dot(d, f.tangent), dot(d, f.bitangent)) / (dist + along);
}

// First atlas texel of VSGL k's tile.
ivec2 ismTileOrigin(IsmParams params, uint k) {
  uint mask = (1u << params.tilesPerRowLog2) - 1u;
  return ivec2(uvec2(k & mask, k >> params.tilesPerRowLog2) * params.mapSize);
}

#ifndef ISM_FRAME_ONLY

// 1 when the receiver at reference distance `ref` is in front of the texel's stored distance.
float ismTexelTest(ivec2 origin, int size, ivec2 texel, float ref) {
  texel = clamp(texel, ivec2(0), ivec2(size - 1));  // stay inside this VSGL's tile
  return ref <= uintBitsToFloat(imageLoad(ismAtlas, origin + texel).r) ? 1.0 : 0.0;
}

// Visibility in [0, 1] of VSGL `vsglIndex` (frame `f`) from the receiver at `position` (world)
// with unit normal `normal` (the side the receiver is seen from, as the G-buffer stores it;
// used only for the slope bias). Receivers of dark VSGLs get 1. Receivers outside the map's
// hemisphere (d_z <= 0, at or behind the plane through the centre normal to the axis), of which
// the map holds nothing, get 1 + d_z |d| / extent clamped to [0, 1]: the VSGL's own surface
// hides it from behind, except from receivers within one standard deviation of its base plane,
// where parts of a curved or folded cluster still face them (a floor-wall corner's wall lights
// the floor beside it). It is continuous at the plane; without it the light of a roof's VSGLs
// reached the room beneath through the roof (docs/techniques/ism.md, "Behind the hemisphere").
// The depth test compares the receiver's distance minus
//   depthBias + slopeBias * (distance * texel angle) * min(tan(receiver angle), ISM_MAX_SLOPE)
// with the stored distance: the slope term is the depth change across one texel's footprint on
// the receiver's plane, the self-occlusion a single point splat can cause. It applies only to
// receivers that face the centre: one that faces away gets no light from it through its own
// surface, so acne there is invisible, while a slope bias would let it see through the front
// faces of its own object at grazing angles.
float ismVisibility(IsmParams params, IsmFrame f, uint vsglIndex, vec3 position, vec3 normal) {
  if (!f.lit) return 1.0;
  vec3 d = position - f.centre;
  float along = dot(d, f.axis);
  if (!(along > 0.0)) return clamp(1.0 + along / max(f.extent, 1e-6), 0.0, 1.0);
  float dist = length(d);
  int size = int(params.mapSize);
  vec2 uv = ismParaboloid(f, d, dist, along);
  float cosReceiver = max(-dot(normal, d) / dist, 0.0);  // 0: faces away, no slope bias
  float tanReceiver = cosReceiver > 0.0
      ? min(sqrt(max(1.0 - cosReceiver * cosReceiver, 0.0)) / cosReceiver, ISM_MAX_SLOPE)
      : 0.0;
  float footprint = dist * 2.0 * (1.0 + along / dist) / float(size);
  float ref = dist - params.depthBias - params.slopeBias * footprint * tanReceiver;
  ivec2 origin = ismTileOrigin(params, vsglIndex);
  // PCF (ISM_PCF_*) as one loop over taps x taps texels from `first`, weights by selects: no
  // branch on the mode, since llvmpipe runs both sides of a branch under masks but a loop
  // only as far as it goes. The shading passes fix the mode at compile time (ISM_LOOKUP_PCF, a
  // specialization constant): the loops then unroll, which keeps a pixel's loop iterations
  // from growing 10-fold with the VSGL count (lavapipe ends an invocation's loops after 65 535
  // of them, docs/performance.md).
  vec2 x = uv * float(size) - 0.5;  // texel-centre coordinates
  bool bilinear = ISM_LOOKUP_PCF == ISM_PCF_BILINEAR;
  int taps = ISM_LOOKUP_PCF == ISM_PCF_NEAREST ? 1 : (bilinear ? 2 : 3);
  ivec2 first = bilinear ? ivec2(floor(x)) : ivec2(uv * float(size)) - taps / 2;
  float sum = 0.0;
  for (int j = 0; j < taps; ++j) {
    float wy = bilinear ? 1.0 - abs(x.y - float(first.y + j)) : 1.0;
    for (int i = 0; i < taps; ++i) {
      float wx = bilinear ? 1.0 - abs(x.x - float(first.x + i)) : 1.0;
      sum += wx * wy * ismTexelTest(origin, size, first + ivec2(i, j), ref);
    }
  }
  // Bilinear weights sum to 1 (up to an fp32 ulp, hence the clamp); box weights to taps^2.
  return min(bilinear ? sum : sum / float(taps * taps), 1.0);
}

float ismVisibility(IsmParams params, Vsgl vsgl, uint vsglIndex, vec3 position, vec3 normal) {
  return ismVisibility(params, ismFrame(vsgl, params.centreOffset), vsglIndex, position, normal);
}

#endif  // ISM_FRAME_ONLY
#endif
