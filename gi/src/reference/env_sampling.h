// BRDF importance sampling and the filtered-importance-sampling (FIS) mip level for environment
// lighting (vsgl-math.md sections 5.1 and 10), in double and naive on purpose: the oracle for the
// GLSL environment-lighting kernel.
//
// This work is based on:
//   [S1] Colbert and Krivanek, "GPU-Based Importance Sampling", GPU Gems 3 ch. 20, 2007 (the
//        Phong lobe sampler, Hammersley points, the level rule with its +1 bias).
//   [S2] Krivanek and Colbert, "Real-time Shading with Filtered Importance Sampling", EGSR 2008
//        (Section 4: the level rule l = max(log4(K w h / (N p r)), 0), K = 4).
//   [W05] Walter, "Notes on the Ward BRDF", Cornell PCG-05-06, 2005 (the anisotropic Ward
//        half-vector sampler and its density).
//   [W07] Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007
//        (GGX: the NDF and its half-vector sampler).
//   [D17] Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
//
// Densities. Every sampler maps u in [0, 1)^2 to a unit direction, and its pdf is a density over
// SOLID ANGLE on the whole sphere (1 / steradian), integrating to 1. Directions may fall below
// the surface (wide lobes, grazing views); the pdf covers them too, and a renderer gives them
// zero weight. A sample is u = 0 -> the lobe's axis: the radial variate is used as 1 - u1, an
// equally uniform variate, so that the Hammersley point k = 0 (u1 = 0) gives the peak of the
// lobe instead of a degenerate horizon sample (Phong, Ward; GGX's usual formula already does).
// Naming: wo points from the surface to the viewer, wi from the surface to the environment
// (the sampled direction); both unit.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

namespace gi {

// ---------------------------------------------------------------------------------------------
// Low-discrepancy points

// Phi_2(k): the bits of k mirrored about the binary point, k = sum b_i 2^i -> sum b_i 2^-(i+1).
// Exact in double for every 32-bit k.
double radicalInverseBase2(uint32_t k);
// Point k of the N-point Hammersley set [S1]: (k / N, Phi_2(k)), in [0, 1)^2 for k < N. For
// N = 2^m every row and every column of the N x N grid holds exactly one point.
glm::dvec2 hammersleyPoint(uint32_t k, uint32_t n);

// ---------------------------------------------------------------------------------------------
// Frames

// An orthonormal right-handed frame (tangent x bitangent = normal).
struct LobeFrame {
  glm::dvec3 tangent{1.0, 0.0, 0.0};
  glm::dvec3 bitangent{0.0, 1.0, 0.0};
  glm::dvec3 normal{0.0, 0.0, 1.0};

  glm::dvec3 toLocal(glm::dvec3 w) const {
    return {glm::dot(w, tangent), glm::dot(w, bitangent), glm::dot(w, normal)};
  }
  glm::dvec3 toWorld(glm::dvec3 w) const { return w.x * tangent + w.y * bitangent + w.z * normal; }
};
// A frame around a unit axis with an arbitrary but deterministic tangent ([D17]'s branchless
// basis: continuous except across axis.z = 0, where its sign flips). For isotropic lobes only.
LobeFrame lobeFrame(glm::dvec3 axis);
// A frame with the given unit normal and the tangent hint projected into its plane
// (Gram-Schmidt): the frame of anisotropic lobes. The hint must not be parallel to the normal.
LobeFrame lobeFrame(glm::dvec3 normal, glm::dvec3 tangentHint);

// Mirror reflection of the unit wo about the unit h: 2 (wo . h) h - wo.
glm::dvec3 reflectAbout(glm::dvec3 wo, glm::dvec3 h);

// ---------------------------------------------------------------------------------------------
// (a) Normalised Phong lobe around the mirror direction [S1]:
//   pdf(wi) = (n + 1) / (2 pi) cos^n theta for cos theta = wi . mirror > 0, else 0,
// sampled as cos theta = (1 - u1)^(1 / (n + 1)), phi = 2 pi u2 in lobeFrame(mirror).
// exponent n >= 0; mirror unit.
glm::dvec3 samplePhong(glm::dvec2 u, glm::dvec3 mirror, double exponent);
double phongPdf(glm::dvec3 wi, glm::dvec3 mirror, double exponent);
// u with samplePhong(u, mirror, n) = wi, for wi . mirror > 0 (u2 in [0, 1)).
glm::dvec2 invertPhong(glm::dvec3 wi, glm::dvec3 mirror, double exponent);

// ---------------------------------------------------------------------------------------------
// (b) Anisotropic Ward, half-vector sampling [W05]. In the frame (tangent = x with roughness
// alphaX, bitangent = y with alphaY, normal = z), with A(phi) = cos^2 phi / ax^2 + sin^2 phi /
// ay^2:
//   p(h) = exp(-tan^2 theta_h A(phi_h)) / (pi ax ay cos^3 theta_h)   (over the solid angle of h,
//          h . n > 0; integrates to exactly 1),
//   phi_h = atan2(ay sin 2 pi u2, ax cos 2 pi u2)   (the quadrant of 2 pi u2 is kept),
//   tan^2 theta_h = -ln(1 - u1) / A(phi_h),
// and wi = reflectAbout(wo, h) with pdf(wi) = p(h) / (4 |wo . h|) (the Jacobian of the
// reflection, d omega_h / d omega_i = 1 / (4 |wo . h|)). alphaX, alphaY > 0.
glm::dvec3 sampleWardHalfVector(glm::dvec2 u, double alphaX, double alphaY);  // frame-local h
double wardHalfVectorPdf(glm::dvec3 hLocal, double alphaX, double alphaY);
glm::dvec2 invertWardHalfVector(glm::dvec3 hLocal, double alphaX, double alphaY);
glm::dvec3 sampleWard(glm::dvec2 u, const LobeFrame& frame, glm::dvec3 wo, double alphaX,
                      double alphaY);
// Every wi has exactly one half vector with h . n > 0 that reflects wo onto it
// (+-normalize(wi + wo)), so the density over wi is well defined on the whole sphere; wi = -wo
// (a set of measure zero) returns 0.
double wardPdf(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alphaX, double alphaY);
glm::dvec2 invertWard(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alphaX,
                      double alphaY);

// ---------------------------------------------------------------------------------------------
// (c) GGX (isotropic alpha), half-vector (NDF) sampling [W07]:
//   D(h) = alpha^2 / (pi ((n . h)^2 (alpha^2 - 1) + 1)^2),  p(h) = D(h) (n . h),
//   tan^2 theta_h = alpha^2 u1 / (1 - u1)  (= cos^2 theta_h = (1 - u1) / (1 + (alpha^2 - 1) u1)),
//   phi_h = 2 pi u2,  pdf(wi) = D(h) (n . h) / (4 |wo . h|).
// alpha > 0 (the caller floors it, e.g. at 1e-3 as brdf.glsl does); the frame's tangent only
// fixes where phi = 0, so lobeFrame(normal) will do.
double ggxD(double cosThetaH, double alpha);
glm::dvec3 sampleGgxHalfVector(glm::dvec2 u, double alpha);  // frame-local h
double ggxHalfVectorPdf(glm::dvec3 hLocal, double alpha);
glm::dvec2 invertGgxHalfVector(glm::dvec3 hLocal, double alpha);
glm::dvec3 sampleGgx(glm::dvec2 u, const LobeFrame& frame, glm::dvec3 wo, double alpha);
double ggxPdf(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alpha);
glm::dvec2 invertGgx(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alpha);

// ---------------------------------------------------------------------------------------------
// FIS mip level ([S2] Section 4, vsgl-math.md section 5.1):
//   l = max(log4(K w h / (N p r)), 0).
// Units: p = the sample's pdf [1 / sr], so 1 / (N p) is the solid angle the sample stands for
// [sr]; r = the map's Jacobian in the direction d omega = r dA [sr per unit texture area], so a
// texel holds r / (w h) [sr]; their ratio w h / (N p r) is the number of level-0 texels the
// sample's solid angle covers [texels], and since each level quarters the texel count, its log4
// is the level whose single texel covers it. K = 4 (the empirical kernel extent of [S2], best
// for box-filtered mips) is [S1]'s "+1" level bias. For the dual paraboloid, w x h is ONE map and
// r = paraboloidSolidAnglePerArea(|z|); for the equirect map, r = equirectSolidAnglePerArea(v).
// p = 0 or r = 0 give +infinity (the caller clamps to the coarsest level); the result is not
// clamped above.
constexpr double kFisKernelExtent = 4.0;
double fisMipLevel(double pdf, double solidAnglePerArea, uint32_t sampleCount, uint32_t width,
                   uint32_t height, double k = kFisKernelExtent);

}  // namespace gi
