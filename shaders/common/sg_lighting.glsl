// SG lighting in fp32: a light SG times the clamped cosine (diffuse, vsgl-math.md section 4.3)
// and times the GGX specular lobe of common/brdf.glsl (glossy, section 4.4). A port of the double
// oracle gi/src/reference/sg_math.cpp with the same structure, names and constants; the
// derivations, the measured errors and the bad regimes are there, in its unit tests
// (tests/unit/test_sg_math.cpp) and in docs/techniques/sg-lighting.md. No bindings of its own: the
// includer declares the buffer of the albedo table (see kSgGgxAlbedoTableSize).
//
// This work is based on:
//   [T22] Tokuyoshi, "Accurate Diffuse Lighting from Spherical Gaussian Lights", 2022, Eq. 1.
//   [T24] Tokuyoshi et al., "Hierarchical Light Sampling with Accurate Spherical Gaussian
//         Lighting", 2024: supplementary Listings 4-7 (vMF hemisphere fraction, SG x clamped
//         cosine) and Section 5.2 (NDF filtering of the GGX reflection lobe by the light).
//   [TK21] Tokuyoshi and Kaplanyan, "Stable Geometric Specular Antialiasing with Projected-Space
//         NDF Filtering", JCGT 2021, Eq. 4 (projected-space roughness).
//   [TH19] Tokuyoshi and Harada, "Hierarchical Russian Roulette for Vertex Connections", 2019,
//         Appendix (the GGX NDF as an SG of sharpness 2 / alpha^2 - 2).
//   [DB23] Dupuy and Benyoub, "Sampling Visible GGX Normals with Spherical Caps", 2023 (the
//         dominant visible normal).
//   [AS64] Abramowitz and Stegun, Handbook of Mathematical Functions, 5.1.53 and 5.1.54 (E1).
//   [NR92] Press et al., Numerical Recipes in C, 2nd ed., Section 6.2 (erfc by Chebyshev fit).
#ifndef SHADERS_COMMON_SG_LIGHTING_GLSL
#define SHADERS_COMMON_SG_LIGHTING_GLSL

#include "sg.glsl"

// ---------------------------------------------------------------------------------------------
// erf and erfc (GLSL has neither).

// erfc(x) = t exp(-x^2 + P(t)), t = 1 / (1 + x / 2), for x >= 0 ([NR92] erfcc): RELATIVE error
// < 1.2e-7 for every x >= 0, so the tail of erfc keeps its digits where 1 - erf would leave none
// (A&S 7.1.26's 1.5e-7 is absolute: useless for erfc(3) = 2e-5). x < 0 by erfc(x) = 2 - erfc(-x).
float sgErfc(float x) {
  float z = abs(x);
  float t = 1.0 / (1.0 + 0.5 * z);
  float p = -1.26551223 + t * (1.00002368 + t * (0.37409196 + t * (0.09678418 +
            t * (-0.18628806 + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 +
            t * (-0.82215223 + t * 0.17087277))))))));
  float r = t * exp(p - z * z);
  return x >= 0.0 ? r : 2.0 - r;
}

// erf(x): below |x| = 0.5 its Taylor series to x^11 (relative error < 3e-8: erf(tau c) / erf(tau)
// below needs relative accuracy as tau -> 0), above 1 - erfc (absolute error < 1e-7, relative
// < 2e-7 there since erf(0.5) = 0.52).
float sgErf(float x) {
  if (abs(x) < 0.5) {
    float x2 = x * x;
    // 2/sqrt(pi) (x - x^3/3 + x^5/10 - x^7/42 + x^9/216 - x^11/1320)
    return 1.1283791671 * x *
           (1.0 + x2 * (-1.0 / 3.0 + x2 * (0.1 + x2 * (-1.0 / 42.0 + x2 * (1.0 / 216.0 +
            x2 * (-1.0 / 1320.0))))));
  }
  float r = 1.0 - sgErfc(abs(x));
  return x >= 0.0 ? r : -r;
}

// ---------------------------------------------------------------------------------------------
// Hemispherical integrals (section 4.2) and SG x clamped cosine (section 4.3).

// [T22] interpolation factor between the lower and upper hemispherical integrals for an SG of
// sharpness lambda whose axis has cosine c with the pole: 1/2 + 1/2 erf(tau c) / erf(tau).
float sgHemisphericalLerpFactor(float sharpness, float cosine) {
  const float A = 0.6517328826907056;
  const float B = 1.3418280033141288;
  const float C = 7.2216687798956709;
  float lambda = sharpness;
  float c = clamp(cosine, -1.0, 1.0);
  // Above 1 the ratio with numerator and denominator divided by lambda^2 (no overflow).
  float tau = lambda <= 1.0
      ? lambda * sqrt((0.5 * lambda + A) / ((lambda + B) * lambda + C))
      : sqrt(lambda) * sqrt((0.5 + A / lambda) / (1.0 + B / lambda + C / (lambda * lambda)));
  if (tau < 1e-30) return 0.5 + 0.5 * c;
  return clamp(0.5 + 0.5 * sgErf(tau * c) / sgErf(tau), 0.0, 1.0);
}

// Fraction of the vMF (normalised SG) that lies above the horizon ([T24] Listing 4):
// (e^-lambda + s (1 - e^-lambda)) / (1 + e^-lambda).
float vmfUpperHemisphereFraction(float sharpness, float cosine) {
  float e = exp(-sharpness);
  return (e + sgHemisphericalLerpFactor(sharpness, cosine) * (1.0 - e)) / (1.0 + e);
}

// U and L of section 4.3 ([T24] Listings 5, 6), per 2 pi: the clamped-cosine integrals of an SG
// whose axis is n (upper) or -n (lower). Below lambda = 0.5 their Taylor series (9 terms:
// truncation < 1e-10), above the closed forms (1 - em1x(-l)) / l and e^-l (em1x(-l) - e^-l) / l.
float clampedCosineUpperIntegral(float sharpness) {
  float l = sharpness;
  if (l <= 0.5) {
    // sum_k (-l)^k / (k + 2)!
    return 1.0 / 2.0 + l * (-1.0 / 6.0 + l * (1.0 / 24.0 + l * (-1.0 / 120.0 + l * (1.0 / 720.0 +
           l * (-1.0 / 5040.0 + l * (1.0 / 40320.0 + l * (-1.0 / 362880.0 +
           l * (1.0 / 3628800.0))))))));
  }
  return (1.0 - em1x(-l)) / l;
}

float clampedCosineLowerIntegral(float sharpness) {
  float l = sharpness;
  float e = exp(-l);
  if (l <= 0.5) {
    // e^-l sum_k (-l)^k (k + 1) / (k + 2)!
    return e * (1.0 / 2.0 + l * (-1.0 / 3.0 + l * (1.0 / 8.0 + l * (-1.0 / 30.0 + l * (1.0 / 144.0 +
           l * (-1.0 / 840.0 + l * (1.0 / 5760.0 + l * (-1.0 / 45360.0 +
           l * (1.0 / 403200.0)))))))));
  }
  return e * (em1x(-l) - e) / l;
}

// D(lambda, c) = (1/pi) integral G(w; xi, lambda) (w . n)^+ dw with xi . n = cosine ([T24]
// Listing 7, section 4.3 option 2): 2 (L + (U - L) s), s clamped to [0, 1]; D(0, c) = 1.
// With a relative-accuracy erfc the [R] clamp s >= eps/2 is not needed.
float sgClampedCosineIntegralOverPi(float sharpness, float cosine) {
  const float A = 2.7360831611272558;
  const float B = 17.021297781741875;
  const float C = 4.0100826728510421;
  const float D = 15.219156263147211;
  const float E = 76.087896272360737;
  float lambda = sharpness;
  float c = clamp(cosine, -1.0, 1.0);
  float t;
  if (lambda <= 1.0) {
    t = lambda * sqrt(0.5 * ((lambda + A) * lambda + B) / (((lambda + C) * lambda + D) * lambda + E));
  } else {
    // Numerator and denominator divided by lambda^3: no overflow up to 2^41.
    float r = 1.0 / lambda;
    t = sqrt(lambda) * sqrt(0.5 * ((B * r + A) * r + 1.0) / (((E * r + D) * r + C) * r + 1.0));
  }
  float s = 0.5 + 0.5 * c;
  if (t >= 1e-30) {
    // exp(-t^2 c^2) expm1(t^2 (c^2 - 1)) / (2 sqrt(pi) t), expm1(x) = x em1x(x).
    float x = t * t * (c * c - 1.0);
    s = 0.5 * (c * sgErfc(-t * c) + sgErfc(t)) -
        exp(-t * t * c * c) * (x * em1x(x)) / (2.0 * 1.7724538509 * t);
  }
  s = clamp(s, 0.0, 1.0);
  float upper = clampedCosineUpperIntegral(lambda);
  float lower = clampedCosineLowerIntegral(lambda);
  return 2.0 * (lower + (upper - lower) * s);
}

// ---------------------------------------------------------------------------------------------
// Glossy (section 4.4): sgGgxReflection and its parts, as sg_math.cpp.

// brdf.glsl's alpha floor and n . v clamp; the view's tangential length below which the view
// counts as normal incidence.
const float kSgGgxMinAlpha = 1e-3;
const float kSgGgxMinViewCosine = 1e-4;
const float kSgGgxMinTangential = 1e-4;
// w = lambda / (lambda + lambda_r + kSgGgxWideLightBias), see sg_math.cpp.
const float kSgGgxWideLightBias = 2.0;
const float kSgFltMax = 3.40282347e38;

// Directional albedo of brdf.glsl's specular lobe, (f0 = 0, f0 = 1), at n . v =
// max((i/16)^2, 1e-4), alpha = max((j/16)^2, 1e-3), index 17 i + j: the table of sg_math.cpp
// (SgMathGlossy.AlbedoTableLayoutMatchesGlsl checks this size against it).
const int kSgGgxAlbedoTableSize = 17;
// The table lives in a storage buffer that the includer declares BEFORE including this file:
//   layout(std430, binding = N) readonly buffer SgGgxAlbedoTable { vec2 kSgGgxAlbedo[]; };
// filled with sg_math.cpp's table (gi::ggxSpecularAlbedoNode): a constant array indexed at run
// time is rebuilt in private memory by every invocation on lavapipe (measured: 4x slower shading).

// sg_math.cpp ggxSpecularAlbedo: the table read bilinearly over (sqrt(n . v), sqrt(alpha)).
vec2 ggxSpecularAlbedo(float nv, float alpha) {
  const float last = float(kSgGgxAlbedoTableSize - 1);
  float u = sqrt(clamp(nv, kSgGgxMinViewCosine, 1.0)) * last;
  float t = sqrt(clamp(alpha, kSgGgxMinAlpha, 1.0)) * last;
  int i = min(int(u), kSgGgxAlbedoTableSize - 2);
  int j = min(int(t), kSgGgxAlbedoTableSize - 2);
  float fu = u - float(i), ft = t - float(j);
  int k = i * kSgGgxAlbedoTableSize + j;
  return mix(mix(kSgGgxAlbedo[k], kSgGgxAlbedo[k + 1], ft),
             mix(kSgGgxAlbedo[k + kSgGgxAlbedoTableSize], kSgGgxAlbedo[k + kSgGgxAlbedoTableSize + 1], ft),
             fu);
}

// sg_math.cpp sgGgxPeakCorrection: (1 + beta)(1 - beta e^beta E1(beta)), E1 by [AS64] 5.1.53
// (beta <= 1) and 5.1.54 (1 < beta <= 100), the asymptotic series above; relative error 1.9e-6
// in double.
float sgGgxPeakCorrection(float beta) {
  if (!(beta > 0.0)) return 1.0;
  if (beta > 100.0) {
    float y = 1.0 / beta;
    return 1.0 + y * (-1.0 + y * (4.0 + y * (-18.0 + y * 96.0)));
  }
  float kappa;
  if (beta <= 1.0) {
    float e1 = -0.57721566 + beta * (0.99999193 + beta * (-0.24991055 + beta * (0.05519968 +
               beta * (-0.00976004 + beta * 0.00107857)))) - log(beta);
    kappa = 1.0 - beta * exp(beta) * e1;
  } else {
    // 1 - P/Q as (Q - P) / Q with the differences of the coefficients (no cancellation).
    float q = (((beta + 9.5733223454) * beta + 25.6329561486) * beta + 21.0996530827) * beta +
              3.9584969228;
    float d = ((0.9999936053 * beta + 7.5739391756) * beta + 12.4648921902) * beta + 3.6907231885;
    kappa = d / q;
  }
  return kappa * (1.0 + beta);
}

// sg_math.cpp ggxVisibilityRatioMean: the mean over an SG lobe of W(c) = 2 c s_v / (c s_v +
// n_v s(c)) (f_spec cos over the reflection pdf, Fresnel aside), as E[c^+] g(E[c | c > 0]);
// upperCosine = E[c | c > 0].
float ggxVisibilityRatioMean(float sharpness, float axisCosine, float nv, float alpha2,
                             out float upperCosine) {
  float meanCosine = kSgPi * sgClampedCosineIntegralOverPi(sharpness, axisCosine) / sgIntegral(sharpness);
  float upper = vmfUpperHemisphereFraction(sharpness, axisCosine);
  float c = upper > 0.0 ? clamp(meanCosine / upper, 0.0, 1.0) : 0.0;
  upperCosine = c;
  float sv = sqrt(alpha2 + (1.0 - alpha2) * nv * nv);
  float sc = sqrt(alpha2 + (1.0 - alpha2) * c * c);
  return meanCosine * 2.0 * sv / (c * sv + nv * sc);
}

// The terms of sgGgxReflection that depend only on the receiver, computed once per pixel
// (sg_math.h SgGgxReceiver): the view frame (ex along the view's tangential part, z = n), the
// view in it, the dominant reflection direction and the reflection SG, and E's constant-light
// end log(A(f0) / W_0).
struct SgGgxReceiver {
  vec3 normal;
  vec3 ex;
  vec3 ey;
  vec3 wo;
  float nv;
  float alpha2;
  float q;
  float reflectionSharpness;
  float reflectionIntegral;  // S(reflectionSharpness)
  vec3 dominantReflection;
  vec3 f0;
  float f90;
  vec3 logWideFactor;
};

// Unit normal and view (surface to viewer); n . v is clamped to 1e-4 as in brdf.glsl.
SgGgxReceiver sgGgxReceiver(vec3 normal, vec3 view, float alpha, vec3 f0, float f90) {
  SgGgxReceiver r;
  r.normal = normal;
  r.f0 = f0;
  r.f90 = f90;
  float a = clamp(alpha, kSgGgxMinAlpha, 1.0);
  r.alpha2 = a * a;
  float nvRaw = dot(normal, view);
  r.nv = max(nvRaw, kSgGgxMinViewCosine);
  vec3 tangential = view - nvRaw * normal;
  float tangentialLength = length(tangential);
  if (tangentialLength > kSgGgxMinTangential) {
    r.ex = tangential / tangentialLength;
  } else {
    vec3 helper = abs(normal.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    r.ex = normalize(cross(helper, normal));
  }
  r.ey = cross(normal, r.ex);
  r.wo = vec3(sqrt(max(1.0 - r.nv * r.nv, 0.0)), 0.0, r.nv);
  // Dominant reflection direction: the view mirrored about the dominant visible normal [DB23].
  float t = sqrt(r.alpha2 * r.wo.x * r.wo.x + r.nv * r.nv);
  vec3 dominantNormal = normalize(vec3(r.alpha2 * r.wo.x, 0.0, t + r.nv));
  r.dominantReflection = 2.0 * dot(r.wo, dominantNormal) * dominantNormal - r.wo;
  // Reflection SG sharpness lambda_r = (1 - alpha^2) / (2 alpha^2) = q / 2 ([TH19], [R]).
  r.q = (1.0 - r.alpha2) / r.alpha2;
  r.reflectionSharpness = 0.5 * r.q;
  r.reflectionIntegral = sgIntegral(r.reflectionSharpness);
  float upperCosineWide;
  float ratioWide = ggxVisibilityRatioMean(r.reflectionSharpness, r.dominantReflection.z, r.nv,
                                           r.alpha2, upperCosineWide);
  vec2 table = ggxSpecularAlbedo(r.nv, a);
  vec3 albedo = f90 * table.x + f0 * (table.y - table.x);  // A(F0, F90), as sg_math.cpp
  r.logWideFactor = log(max(albedo, vec3(kSgFltMin)) / max(ratioWide, kSgFltMin));
  return r;
}

// integral G(w; light.axis, light.sharpness) f_spec(w, view) (w . n)^+ dw for a UNIT-amplitude SG
// (light.logAmplitude is ignored), f_spec brdf.glsl's specular lobe (GGX alpha floored at 1e-3,
// height-correlated Smith, Schlick with f0) of the receiver r. Step by step as sg_math.cpp
// sgGgxReflection:
//   K = c(beta) (w K_sharp + (1 - w) K_wide),   E = W_q F(v . h_q)^w (A(f0) / W_0)^(1 - w).
vec3 sgGgxReflection(Sg light, SgGgxReceiver r) {
  float lambda = max(light.sharpness, 0.0);
  float nv = r.nv, q = r.q;
  vec3 wo = r.wo;
  vec3 xi = vec3(dot(light.axis, r.ex), dot(light.axis, r.ey), dot(light.axis, r.normal));

  // K, sharp part: [T24] NDF filtering, diagonal in the view frame: m_i = b_i / (lambda q + b_i)
  // with b = (lambda + q/2, lambda + q / (2 n_v^2)); the symmetric-GGX reflection pdf with
  // roughness diag(m1, m2) at the half vector of the view and the light axis.
  float lq = lambda * q;
  float b1 = lambda + 0.5 * q;
  float b2 = lambda + 0.5 * q / (nv * nv);
  float m1 = lq + b1 > 0.0 ? b1 / (lq + b1) : 1.0;
  float m2 = lq + b2 > 0.0 ? b2 / (lq + b2) : 1.0;
  vec3 halfSum = wo + xi;
  float halfLength = length(halfSum);
  vec3 h = halfLength > 0.0 ? halfSum / halfLength : vec3(0.0, 0.0, 1.0);
  float stretched = h.x * h.x / m1 + h.y * h.y / m2 + h.z * h.z;
  float ndf = 1.0 / (kSgPi * sqrt(m1 * m2) * stretched * stretched);
  float filteredPdf = ndf / (4.0 * sqrt(m1 * wo.x * wo.x + nv * nv));
  float sharpMass = sgIntegral(lambda) * filteredPdf;

  // K, wide part: the SG inner product of the light with the normalised reflection SG.
  Sg product = sgProduct(Sg(xi, lambda, 0.0), Sg(r.dominantReflection, r.reflectionSharpness, 0.0));
  float wideMass = exp(product.logAmplitude) * sgIntegral(product.sharpness) / r.reflectionIntegral;

  // The blend and the small-angle t x Gaussian peak correction, beta = lambda / q.
  float w = lambda / (lambda + r.reflectionSharpness + kSgGgxWideLightBias);
  float beta = q > 0.0 ? lambda / q : kSgFltMax;
  float mass = sgGgxPeakCorrection(beta) * (w * sharpMass + (1.0 - w) * wideMass);

  // E: visibility ratio over the product lobe, Fresnel at the half vector of its lit part, pulled
  // towards the tabulated albedo over the same model's constant-light value as the light widens.
  float upperCosine;
  float ratio = ggxVisibilityRatioMean(product.sharpness, product.axis.z, nv, r.alpha2, upperCosine);
  // Fresnel at the product axis moved to the mean cosine of its part above the horizon.
  float horizontal = length(vec2(product.axis.x, product.axis.y));
  float sine = sqrt(max(1.0 - upperCosine * upperCosine, 0.0));
  vec3 fresnelAxis = horizontal > 0.0 ? vec3(product.axis.x / horizontal * sine,
                                             product.axis.y / horizontal * sine, upperCosine)
                                      : vec3(0.0, 0.0, 1.0);
  vec3 lobeHalf = wo + fresnelAxis;
  float lobeHalfLength = length(lobeHalf);
  float vh = lobeHalfLength > 0.0 ? dot(wo, lobeHalf) / lobeHalfLength : 0.0;
  float m = 1.0 - max(vh, 0.0);
  float m2s = m * m;
  vec3 fresnel = r.f0 + (r.f90 - r.f0) * (m2s * m2s * m);
  vec3 logE = w * log(max(fresnel, vec3(kSgFltMin))) + (1.0 - w) * r.logWideFactor;
  return mass * ratio * exp(logE);
}

#endif
