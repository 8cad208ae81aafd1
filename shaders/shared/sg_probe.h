// The SG-function probe (shaders/probe/sg_probe.comp), a test harness: each case names one fp32
// function of shaders/common and its inputs, and gets that function's outputs back, so that the
// stability suite (tests/gpu/test_stability_sg.cpp) can hold every hard input of vsgl-math.md
// section 12 against the double oracles of gi/src/reference on the GPU itself.
#ifndef SHADERS_SHARED_SG_PROBE_H
#define SHADERS_SHARED_SG_PROBE_H
#include "interop.h"

#define SG_PROBE_GROUP 8

// Functions (SgProbeCase::function), inputs in a, b, c and outputs in x, y:
//   EM1X             a.x = x -> x.x = em1x(x)
//   INTEGRAL         a.x = lambda -> x.x = S(lambda)
//   PRODUCT          a, b = (axis, lambda) -> x = (axis, lambda), y.x = log amplitude
//   CLAMPED_COSINE   a.x = lambda, a.y = cosine -> x = (D, U, L, vMF upper fraction)
//   BANERJEE         a.x = mean length r, a.y = lambda -> x.x = kappa(r), x.y = r(lambda)
//   MEAN_AXIS        a.xyz = mean axis -> x = (axis, sharpness)
//   VSGL_RADIANCE    a = (mean, variance), b = (axis, sharpness), c = (receiver, log scale)
//                    -> x = (axis, sharpness), y.x = log amplitude
//   GGX_REFLECTION   a = (light axis, lambda), b = (normal, alpha), c = (view, f0) -> x.xyz
//   VPL_SPECULAR     a = (normal, roughness), b.xyz = to light -> x = (axis, sharpness)
//   VSGL_BOUND       a = (mean, variance), b = (axis, sharpness), c = (centre, radius),
//                    d = (normal axis, normal angle), e = (log scale, albedo, fresnel, alpha),
//                    f.xy = (view cosine, specular albedo)
//                    -> x.xy = (diffuse, glossy) bounds (common/vsgl_bound.glsl)
#define SG_PROBE_EM1X 0u
#define SG_PROBE_INTEGRAL 1u
#define SG_PROBE_PRODUCT 2u
#define SG_PROBE_CLAMPED_COSINE 3u
#define SG_PROBE_BANERJEE 4u
#define SG_PROBE_MEAN_AXIS 5u
#define SG_PROBE_VSGL_RADIANCE 6u
#define SG_PROBE_GGX_REFLECTION 7u
#define SG_PROBE_VPL_SPECULAR 8u
#define SG_PROBE_VSGL_BOUND 9u

SHARED_BEGIN

struct SgProbeCase {
  vec4 a;
  vec4 b;
  vec4 c;
  vec4 d;
  vec4 e;
  vec4 f;
  uint function;
  uint pad0, pad1, pad2;
};

struct SgProbeResult {
  vec4 x;
  vec4 y;
};

struct SgProbePush {
  uint count;
  uint pad0, pad1, pad2;
};

SHARED_END

SHARED_ASSERT_SIZE(SgProbeCase, 112);
SHARED_ASSERT_OFFSET(SgProbeCase, function, 96);
SHARED_ASSERT_SIZE(SgProbeResult, 32);
SHARED_ASSERT_SIZE(SgProbePush, 16);
#endif
