#version 460
// The SG-function probe (shaders/shared/sg_probe.h): one thread per case calls the named fp32
// function of shaders/common, the same code the passes run, and writes its outputs. CPU twins:
// the double oracles of gi/src/reference (sg_math.h, vsgl_sampling.h), held against it by
// tests/gpu/test_stability_sg.cpp.
#extension GL_GOOGLE_include_directive : require

#include "shared/sg_probe.h"

layout(local_size_x = SG_PROBE_GROUP) in;
layout(std430, binding = 0) readonly buffer Cases { SgProbeCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { SgProbeResult results[]; };
layout(std430, binding = 2) readonly buffer SgGgxAlbedoTable { vec2 kSgGgxAlbedo[]; };
layout(push_constant) uniform Push { SgProbePush pc; };

#include "common/sg_lighting.glsl"
#include "common/vsgl_bound.glsl"
#include "common/vsgl_lobes.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  SgProbeCase p = cases[i];
  vec4 x = vec4(0.0), y = vec4(0.0);
  if (p.function == SG_PROBE_EM1X) {
    x.x = em1x(p.a.x);
  } else if (p.function == SG_PROBE_INTEGRAL) {
    x.x = sgIntegral(p.a.x);
  } else if (p.function == SG_PROBE_PRODUCT) {
    Sg s = sgProduct(Sg(p.a.xyz, p.a.w, 0.0), Sg(p.b.xyz, p.b.w, 0.0));
    x = vec4(s.axis, s.sharpness);
    y.x = s.logAmplitude;
  } else if (p.function == SG_PROBE_CLAMPED_COSINE) {
    x = vec4(sgClampedCosineIntegralOverPi(p.a.x, p.a.y), clampedCosineUpperIntegral(p.a.x),
             clampedCosineLowerIntegral(p.a.x), vmfUpperHemisphereFraction(p.a.x, p.a.y));
  } else if (p.function == SG_PROBE_BANERJEE) {
    x.xy = vec2(banerjeeSharpness(p.a.x), banerjeeMeanLength(p.a.y));
  } else if (p.function == SG_PROBE_MEAN_AXIS) {
    vec3 axis;
    float sharpness;
    lobeFromMeanAxis(p.a.xyz, axis, sharpness);
    x = vec4(axis, sharpness);
  } else if (p.function == SG_PROBE_VSGL_RADIANCE) {
    Sg s = vsglIncomingRadiance(p.a.xyz, p.a.w, p.b.xyz, p.b.w, p.c.w, p.c.xyz,
                                vec4(0.0, 0.0, 0.0, 1.0));
    x = vec4(s.axis, s.sharpness);
    y.x = s.logAmplitude;
  } else if (p.function == SG_PROBE_GGX_REFLECTION) {
    SgGgxReceiver r = sgGgxReceiver(p.b.xyz, p.c.xyz, p.b.w, vec3(p.c.w), 1.0);
    x.xyz = sgGgxReflection(Sg(p.a.xyz, p.a.w, 0.0), r);
  } else if (p.function == SG_PROBE_VPL_SPECULAR) {
    vec3 axis;
    float sharpness;
    vplSpecularLobe(p.a.xyz, p.b.xyz, p.a.w, axis, sharpness);
    x = vec4(axis, sharpness);
  } else if (p.function == SG_PROBE_VSGL_BOUND) {
    VsglReceivers r = VsglReceivers(p.c.xyz, p.c.w, p.d.xyz, p.d.w, p.e.y, p.e.z, p.e.w, p.f.x, p.f.y);
    x.xy = vsglLobeBound(p.a.xyz, p.a.w, p.b.xyz, p.b.w, p.e.x, r);
  }
  results[i] = SgProbeResult(x, y);
}
