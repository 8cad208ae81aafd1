// Spherical Gaussian math in fp32 with the stable forms of vsgl-math.md section 4.2. The double
// oracle is gi/src/reference/sg_math.cpp; names and conventions follow it:
// G(w; axis, sharpness) = exp(sharpness (w . axis - 1)), amplitudes kept as logarithms.
#ifndef SHADERS_COMMON_SG_GLSL
#define SHADERS_COMMON_SG_GLSL

const float kSgPi = 3.14159265358979;
const float kSgFltMin = 1.17549435e-38;
// v >= d^2 / 2^41 (section 4.1): the spot sharpness d^2 / v stays <= VSGL_MAX_SHARPNESS.
const float kSgVarianceFloorScale = 4.5474735e-13;

// (e^x - 1) / x (section 4.2). Below |x| = 1 its Taylor series sum x^k / (k + 1)!, k <= 10
// (truncation < 1 / 12! = 2.1e-9, so the two branches meet to fp32 rounding), above the plain
// quotient, which no longer cancels. The double oracle's Higham/Kahan form (u - 1) / log(u)
// needs a log accurate to an ulp of u - 1 at u = e^x near 1; lavapipe's log is only absolutely
// accurate there, and that form read em1x(1e-7) = 1.19 and em1x(-1e-30) = 6e22, so S(1e-8)
// was 37 instead of 4 pi (tests/gpu/test_stability_sg.cpp, section 12 case 9).
float em1x(float x) {
  if (abs(x) < 1.0) {
    return 1.0 + x * (1.0 / 2.0 + x * (1.0 / 6.0 + x * (1.0 / 24.0 + x * (1.0 / 120.0 +
           x * (1.0 / 720.0 + x * (1.0 / 5040.0 + x * (1.0 / 40320.0 + x * (1.0 / 362880.0 +
           x * (1.0 / 3628800.0 + x * (1.0 / 39916800.0))))))))));
  }
  return (exp(x) - 1.0) / x;
}

// Integral of G over the sphere, 4 pi em1x(-2 lambda): 4 pi at lambda = 0, 2 pi / lambda for large.
// Above lambda = 8 the dropped e^(-2 lambda) < 1.2e-7 is below fp32 rounding: the exp is skipped.
float sgIntegral(float sharpness) {
  return sharpness > 8.0 ? 2.0 * kSgPi / sharpness : 4.0 * kSgPi * em1x(-2.0 * sharpness);
}

struct Sg {
  vec3 axis;  // unit
  float sharpness;
  float logAmplitude;
};

// The product of two SGs (section 4.2) with the log amplitude in its cancellation-free form
// -l1 l2 |xi1 - xi2|^2 / (|u| + l1 + l2). |u| = 0 (opposite axes with equal sharpness, or both
// sharpnesses 0) makes the product constant: any unit axis is exact, a.axis is kept.
Sg sgProduct(Sg a, Sg b) {
  vec3 u = a.sharpness * a.axis + b.sharpness * b.axis;
  Sg p;
  p.sharpness = length(u);
  p.axis = p.sharpness > 0.0 ? u / p.sharpness : a.axis;
  vec3 gap = a.axis - b.axis;
  float denominator = p.sharpness + a.sharpness + b.sharpness;
  float logProduct = denominator > 0.0 ? -a.sharpness * b.sharpness * dot(gap, gap) / denominator : 0.0;
  p.logAmplitude = a.logAmplitude + b.logAmplitude + logProduct;
  return p;
}

// Integral of the product over the sphere, e^(l_p) S(lambda_p), with `logScale` folded into the
// exponent so that a huge scale and a tiny overlap never overflow apart.
float sgInnerProduct(Sg a, Sg b, float logScale) {
  Sg p = sgProduct(a, b);
  return exp(p.logAmplitude + logScale) * sgIntegral(p.sharpness);
}

// The positional Gaussian of a VSGL lobe seen from `receiver` (section 4.1): the planar spot
// G(w; l / d, d^2 / v_f), v_f = max(f v, d^2 / 2^41, FLT_MIN), so that single-texel
// (zero-variance) lobes and a receiver at the mean stay finite, with logAmplitude = log(f / v_f)
// (-inf where f = 0). f = plane.w + (plane.xyz . (receiver - mean))^+ / sqrt(d^2 + v) is the
// emitter's foreshortening (common/vsgl_emitter.glsl: the elevation's cosine, measured against
// the cluster's own size near it); plane = (0, 0, 0, 1), f = 1, for the SG emitter of section 3.4.
// At d = 0 the sharpness is 0 and the axis (`fallbackAxis`) irrelevant (case 12).
Sg vsglSpot(vec3 mean, float variance, vec3 receiver, vec4 plane, vec3 fallbackAxis) {
  vec3 toLight = mean - receiver;
  float distance2 = dot(toLight, toLight);
  float distance = sqrt(distance2);
  float reach = sqrt(distance2 + variance);
  float foreshortening =
      plane.w + (reach > 0.0 ? max(-dot(plane.xyz, toLight), 0.0) / reach : 0.0);
  float spotVariance =
      max(max(foreshortening * variance, distance2 * kSgVarianceFloorScale), kSgFltMin);
  float ratio = foreshortening / spotVariance;  // <= 1 / FLT_MIN: finite
  return Sg(distance > 0.0 ? toLight / distance : fallbackAxis, distance2 / spotVariance,
            ratio > 0.0 ? log(ratio) : -1.0 / 0.0);
}

// Incoming radiance at `receiver` from a VSGL lobe (section 4.1): the emitted lobe seen back
// along -axis times the lobe's spot (vsglSpot). The result's logAmplitude includes
// log E = logScale + log(f / v_f), where logScale = log(power / (2 pi N)) is per lobe (computed
// apart so loops can hoist it); N = S(sharpness) for the SG emitter, the emission's
// normalisation for a planar one (common/vsgl_emitter.glsl).
Sg vsglIncomingRadiance(vec3 mean, float variance, vec3 axis, float sharpness, float logScale,
                        vec3 receiver, vec4 plane) {
  Sg spot = vsglSpot(mean, variance, receiver, plane, -axis);
  Sg radiance = sgProduct(Sg(-axis, sharpness, 0.0), spot);
  radiance.logAmplitude += logScale;
  return radiance;
}

#endif
