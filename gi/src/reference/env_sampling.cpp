#include "reference/env_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;

// u2 = phi / (2 pi) wrapped into [0, 1): the inverse of phi = 2 pi u2.
double azimuthToUnit(double phi) {
  double u = phi / (2.0 * kPi);
  u -= std::floor(u);
  return u >= 1.0 ? 0.0 : u;
}

// Unit vector with polar angle given by (cos, sin) and azimuth phi, in a frame's local axes.
glm::dvec3 sphericalLocal(double cosTheta, double sinTheta, double phi) {
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

// The half vector with h . n > 0 that reflects wo onto wi (both world, unit), in frame-local
// coordinates; false for wi = -wo, where wi + wo vanishes and no single h exists.
bool halfVectorLocal(glm::dvec3 wi, glm::dvec3 wo, const LobeFrame& frame, glm::dvec3& hLocal) {
  const glm::dvec3 sum = frame.toLocal(wi + wo);
  const double length = glm::length(sum);
  if (!(length > 0.0)) return false;
  hLocal = sum / length;
  if (hLocal.z < 0.0) hLocal = -hLocal;  // -h reflects wo onto the same wi
  return true;
}

// pdf over wi from a half-vector density: p(h) / (4 |wo . h|), the reflection's Jacobian.
double reflectedPdf(double halfPdf, glm::dvec3 woLocal, glm::dvec3 hLocal) {
  const double woh = std::abs(glm::dot(woLocal, hLocal));
  return woh > 0.0 ? halfPdf / (4.0 * woh) : 0.0;
}

// Ward's A(phi) tan^2 theta for a local half vector, (hx^2 / ax^2 + hy^2 / ay^2) / hz^2: no
// trigonometry, so it stays accurate near the pole where phi is ill-conditioned.
double wardExponent(glm::dvec3 h, double alphaX, double alphaY) {
  const double x = h.x / alphaX, y = h.y / alphaY;
  return (x * x + y * y) / (h.z * h.z);
}

}  // namespace

double radicalInverseBase2(uint32_t k) {
  // Swap halves, bytes, nibbles, pairs and bits: the 32-bit reversal, then scale by 2^-32.
  k = (k << 16) | (k >> 16);
  k = ((k & 0x00ff00ffu) << 8) | ((k & 0xff00ff00u) >> 8);
  k = ((k & 0x0f0f0f0fu) << 4) | ((k & 0xf0f0f0f0u) >> 4);
  k = ((k & 0x33333333u) << 2) | ((k & 0xccccccccu) >> 2);
  k = ((k & 0x55555555u) << 1) | ((k & 0xaaaaaaaau) >> 1);
  return double(k) * 0x1p-32;
}

glm::dvec2 hammersleyPoint(uint32_t k, uint32_t n) {
  return {double(k) / double(n), radicalInverseBase2(k)};
}

LobeFrame lobeFrame(glm::dvec3 axis) {
  // [D17] Listing 3: the sign picks the hemisphere so that 1 / (sign + z) never divides by ~0.
  const double sign = std::copysign(1.0, axis.z);
  const double a = -1.0 / (sign + axis.z);
  const double b = axis.x * axis.y * a;
  LobeFrame frame;
  frame.tangent = {1.0 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x};
  frame.bitangent = {b, sign + axis.y * axis.y * a, -axis.y};
  frame.normal = axis;
  return frame;
}

LobeFrame lobeFrame(glm::dvec3 normal, glm::dvec3 tangentHint) {
  LobeFrame frame;
  frame.normal = normal;
  frame.tangent = glm::normalize(tangentHint - glm::dot(tangentHint, normal) * normal);
  frame.bitangent = glm::cross(normal, frame.tangent);
  return frame;
}

glm::dvec3 reflectAbout(glm::dvec3 wo, glm::dvec3 h) {
  return 2.0 * glm::dot(wo, h) * h - wo;
}

// ---------------------------------------------------------------------------------------------
// Phong

glm::dvec3 samplePhong(glm::dvec2 u, glm::dvec3 mirror, double exponent) {
  // The CDF of cos theta on [0, 1] under (n + 1) cos^n is cos^(n + 1); with 1 - u1 in place of
  // u1 (file comment), u1 = 0 is the mirror direction. sin from 1 - cos^2 = (1 - c)(1 + c).
  const double cosTheta = std::pow(1.0 - u.x, 1.0 / (exponent + 1.0));
  const double sinTheta = std::sqrt(std::max(0.0, (1.0 - cosTheta) * (1.0 + cosTheta)));
  return lobeFrame(mirror).toWorld(sphericalLocal(cosTheta, sinTheta, 2.0 * kPi * u.y));
}

double phongPdf(glm::dvec3 wi, glm::dvec3 mirror, double exponent) {
  const double c = glm::dot(wi, mirror);
  return c > 0.0 ? (exponent + 1.0) / (2.0 * kPi) * std::pow(c, exponent) : 0.0;
}

glm::dvec2 invertPhong(glm::dvec3 wi, glm::dvec3 mirror, double exponent) {
  const glm::dvec3 local = lobeFrame(mirror).toLocal(wi);
  const double c = std::clamp(local.z, 0.0, 1.0);
  // 1 - c^(n + 1) as -expm1((n + 1) log c): exact for c near 1, where large n lives.
  const double u1 = c > 0.0 ? -std::expm1((exponent + 1.0) * std::log(c)) : 1.0;
  return {u1, azimuthToUnit(std::atan2(local.y, local.x))};
}

// ---------------------------------------------------------------------------------------------
// Ward

glm::dvec3 sampleWardHalfVector(glm::dvec2 u, double alphaX, double alphaY) {
  // [W05]: phi_h = atan((ay / ax) tan 2 pi u2) taken in the quadrant of 2 pi u2, which is
  // atan2(ay sin, ax cos); then theta_h from the exponential conditional in tan^2 theta.
  const double psi = 2.0 * kPi * u.y;
  const double phi = std::atan2(alphaY * std::sin(psi), alphaX * std::cos(psi));
  const double cosPhi = std::cos(phi), sinPhi = std::sin(phi);
  const double a = cosPhi * cosPhi / (alphaX * alphaX) + sinPhi * sinPhi / (alphaY * alphaY);
  // -ln(1 - u1) as -log1p(-u1): exact for small u1 (the lobe's peak).
  const double tan2 = -std::log1p(-u.x) / a;
  const double cosTheta = 1.0 / std::sqrt(1.0 + tan2);
  const double sinTheta = std::sqrt(tan2) * cosTheta;
  return sphericalLocal(cosTheta, sinTheta, phi);
}

double wardHalfVectorPdf(glm::dvec3 hLocal, double alphaX, double alphaY) {
  if (!(hLocal.z > 0.0)) return 0.0;
  const double c = hLocal.z;
  return std::exp(-wardExponent(hLocal, alphaX, alphaY)) / (kPi * alphaX * alphaY * c * c * c);
}

glm::dvec2 invertWardHalfVector(glm::dvec3 hLocal, double alphaX, double alphaY) {
  // tan^2 theta A(phi) = -ln(1 - u1), and the quadrant-keeping inverse of phi: the sampler sets
  // (cos phi, sin phi) proportional to (ax cos psi, ay sin psi), so (cos psi, sin psi) is
  // proportional to (cos phi / ax, sin phi / ay), i.e. to (h_x / ax, h_y / ay).
  const double u1 = -std::expm1(-wardExponent(hLocal, alphaX, alphaY));
  const double psi = std::atan2(hLocal.y / alphaY, hLocal.x / alphaX);
  return {u1, azimuthToUnit(psi)};
}

glm::dvec3 sampleWard(glm::dvec2 u, const LobeFrame& frame, glm::dvec3 wo, double alphaX,
                      double alphaY) {
  const glm::dvec3 h = frame.toWorld(sampleWardHalfVector(u, alphaX, alphaY));
  return reflectAbout(wo, h);
}

double wardPdf(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alphaX, double alphaY) {
  glm::dvec3 h;
  if (!halfVectorLocal(wi, wo, frame, h)) return 0.0;
  return reflectedPdf(wardHalfVectorPdf(h, alphaX, alphaY), frame.toLocal(wo), h);
}

glm::dvec2 invertWard(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alphaX,
                      double alphaY) {
  glm::dvec3 h{0.0, 0.0, 1.0};
  halfVectorLocal(wi, wo, frame, h);
  return invertWardHalfVector(h, alphaX, alphaY);
}

// ---------------------------------------------------------------------------------------------
// GGX

double ggxD(double cosThetaH, double alpha) {
  if (!(cosThetaH > 0.0)) return 0.0;
  const double a2 = alpha * alpha;
  // (n.h)^2 (a^2 - 1) + 1 = cos^2 a^2 + sin^2: both terms >= 0, no cancellation for small alpha.
  const double c2 = cosThetaH * cosThetaH;
  const double d = c2 * a2 + (1.0 - c2);
  return a2 / (kPi * d * d);
}

glm::dvec3 sampleGgxHalfVector(glm::dvec2 u, double alpha) {
  // [W07] Eq. 35 in the tan form: tan^2 theta = alpha^2 u1 / (1 - u1).
  const double tan2 = alpha * alpha * u.x / (1.0 - u.x);
  const double cosTheta = 1.0 / std::sqrt(1.0 + tan2);
  const double sinTheta = std::sqrt(tan2) * cosTheta;
  return sphericalLocal(cosTheta, sinTheta, 2.0 * kPi * u.y);
}

double ggxHalfVectorPdf(glm::dvec3 hLocal, double alpha) {
  if (!(hLocal.z > 0.0)) return 0.0;
  // D written with sin^2 = x^2 + y^2 rather than 1 - z^2, exact near the pole.
  const double a2 = alpha * alpha;
  const double s2 = hLocal.x * hLocal.x + hLocal.y * hLocal.y;
  const double d = hLocal.z * hLocal.z * a2 + s2;
  return a2 / (kPi * d * d) * hLocal.z;
}

glm::dvec2 invertGgxHalfVector(glm::dvec3 hLocal, double alpha) {
  // u1 = tan^2 / (tan^2 + alpha^2) = sin^2 / (sin^2 + alpha^2 cos^2).
  const double s2 = hLocal.x * hLocal.x + hLocal.y * hLocal.y;
  const double u1 = s2 / (s2 + alpha * alpha * hLocal.z * hLocal.z);
  return {u1, azimuthToUnit(std::atan2(hLocal.y, hLocal.x))};
}

glm::dvec3 sampleGgx(glm::dvec2 u, const LobeFrame& frame, glm::dvec3 wo, double alpha) {
  return reflectAbout(wo, frame.toWorld(sampleGgxHalfVector(u, alpha)));
}

double ggxPdf(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alpha) {
  glm::dvec3 h;
  if (!halfVectorLocal(wi, wo, frame, h)) return 0.0;
  return reflectedPdf(ggxHalfVectorPdf(h, alpha), frame.toLocal(wo), h);
}

glm::dvec2 invertGgx(glm::dvec3 wi, const LobeFrame& frame, glm::dvec3 wo, double alpha) {
  glm::dvec3 h{0.0, 0.0, 1.0};
  halfVectorLocal(wi, wo, frame, h);
  return invertGgxHalfVector(h, alpha);
}

// ---------------------------------------------------------------------------------------------
// FIS level

double fisMipLevel(double pdf, double solidAnglePerArea, uint32_t sampleCount, uint32_t width,
                   uint32_t height, double k) {
  const double denominator = double(sampleCount) * pdf * solidAnglePerArea;
  if (!(denominator > 0.0)) return std::numeric_limits<double>::infinity();
  // log4(x) = log2(x) / 2; the texel count K w h / (N p r) is derived in the header.
  const double texels = k * double(width) * double(height) / denominator;
  return std::max(0.5 * std::log2(texels), 0.0);
}

}  // namespace gi
