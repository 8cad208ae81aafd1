#include "reference/sg_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace gi {

namespace {

constexpr double kPi = std::numbers::pi;
// Below these the interpolation factors are replaced by their lambda -> 0 limit, (1 + c) / 2:
// the ratios they guard are 0 / 0 at 0, and the limit is exact to O(tau^2) = 1e-200.
constexpr double kTinySteepness = 1e-100;
// The Taylor branch of U and L (section 4.3): below 0.5 the closed forms lose digits to
// cancellation (about eps * 0.5 / U at the switch, 5e-16, so the branches meet continuously).
constexpr double kTaylorSwitch = 0.5;
// Terms of the Taylor series: the k-th term is at most 0.5^k / (k + 2)!, below 1e-19 of the
// leading 1/2 from k = 15 on, so 16 terms are exact in double.
constexpr int kTaylorTerms = 16;

glm::dvec3 safeNormalize(glm::dvec3 v, glm::dvec3 fallback) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : fallback;
}

// sum_k coefficient(k) lambda^k for k < kTaylorTerms, by Horner from the smallest term.
template <typename Coefficient>
double taylor(double lambda, Coefficient coefficient) {
  double sum = 0.0;
  for (int k = kTaylorTerms - 1; k >= 0; --k) sum = sum * lambda + coefficient(k);
  return sum;
}

// 1 / n! in double.
double inverseFactorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) f *= double(i);
  return 1.0 / f;
}

}  // namespace

double em1x(double x) {
  // expm1 carries full relative accuracy to the smallest subnormals, so only x = 0 is special.
  return x == 0.0 ? 1.0 : std::expm1(x) / x;
}

double sgIntegral(double lambda) {
  return 4.0 * kPi * em1x(-2.0 * lambda);
}

double sgEvaluate(glm::dvec3 omega, glm::dvec3 axis, double lambda) {
  const glm::dvec3 d = omega - axis;
  return std::exp(-0.5 * lambda * glm::dot(d, d));
}

double sgEvaluate(const Sg& sg, glm::dvec3 omega) {
  const glm::dvec3 d = omega - sg.axis;
  return std::exp(sg.logAmplitude - 0.5 * sg.sharpness * glm::dot(d, d));
}

Sg sgProduct(const Sg& a, const Sg& b) {
  const glm::dvec3 u = a.sharpness * a.axis + b.sharpness * b.axis;
  // |u| through the largest component: the same as sqrt(u . u), but without underflow for
  // nearly cancelling lobes, so the axis stays unit down to subnormal |u|.
  const double largest = std::max({std::abs(u.x), std::abs(u.y), std::abs(u.z)});
  Sg p;
  if (largest > 0.0) {
    const glm::dvec3 scaled = u / largest;
    const double length = glm::length(scaled);
    p.sharpness = largest * length;
    p.axis = scaled / length;
  } else {
    // Opposite axes with equal sharpness, or both sharpnesses 0: the product is constant over
    // the sphere, and any unit axis is exact (section 12 case 8).
    p.sharpness = 0.0;
    p.axis = a.axis;
  }
  // l_p = lambda_p - l1 - l2, in the form of section 4.2 that does not cancel when both lobes
  // are sharp; the denominator is 0 only when every sharpness is 0, where l_p = 0.
  const glm::dvec3 gap = a.axis - b.axis;
  const double denominator = p.sharpness + a.sharpness + b.sharpness;
  const double logProduct =
      denominator > 0.0 ? -a.sharpness * b.sharpness * glm::dot(gap, gap) / denominator : 0.0;
  p.logAmplitude = a.logAmplitude + b.logAmplitude + logProduct;
  return p;
}

double sgInnerProduct(const Sg& a, const Sg& b) {
  const Sg p = sgProduct(a, b);
  return std::exp(p.logAmplitude) * sgIntegral(p.sharpness);
}

double sgUpperHemisphericalIntegral(double lambda) {
  return em1x(-lambda);
}

double sgLowerHemisphericalIntegral(double lambda) {
  return std::exp(-lambda) * em1x(-lambda);
}

double sgHemisphericalLerpFactor(double lambda, double cosine) {
  // [T22] fit constants, section 4.2.
  constexpr double kA = 0.6517328826907056;
  constexpr double kB = 1.3418280033141288;
  constexpr double kC = 7.2216687798956709;
  const double c = std::clamp(cosine, -1.0, 1.0);
  // tau = lambda sqrt((lambda/2 + A) / ((lambda + B) lambda + C)); above 1 the same ratio with
  // numerator and denominator divided by lambda^2, so that huge lambda cannot overflow.
  const double tau =
      lambda <= 1.0 ? lambda * std::sqrt((0.5 * lambda + kA) / ((lambda + kB) * lambda + kC))
                    : std::sqrt(lambda) * std::sqrt((0.5 + kA / lambda) /
                                                    (1.0 + kB / lambda + kC / (lambda * lambda)));
  if (tau < kTinySteepness) return 0.5 + 0.5 * c;
  return std::clamp(0.5 + 0.5 * std::erf(tau * c) / std::erf(tau), 0.0, 1.0);
}

double sgHemisphericalIntegral(double lambda, double cosine) {
  const double upper = sgUpperHemisphericalIntegral(lambda);
  const double lower = sgLowerHemisphericalIntegral(lambda);
  return lower + sgHemisphericalLerpFactor(lambda, cosine) * (upper - lower);
}

double vmfUpperHemisphereFraction(double lambda, double cosine) {
  // The em1x(-lambda) common to H_up and H_low cancels against the vMF normalisation.
  const double e = std::exp(-lambda);
  return (e + sgHemisphericalLerpFactor(lambda, cosine) * (1.0 - e)) / (1.0 + e);
}

double clampedCosineUpperIntegral(double lambda) {
  // U = integral_0^1 mu e^(lambda (mu - 1)) d mu = (lambda - 1 + e^-lambda) / lambda^2
  //   = sum_k (-lambda)^k / (k + 2)!  (expanding e^-lambda).
  if (lambda <= kTaylorSwitch) {
    return taylor(lambda,
                  [](int k) { return (k % 2 == 0 ? 1.0 : -1.0) * inverseFactorial(k + 2); });
  }
  return (1.0 - em1x(-lambda)) / lambda;
}

double clampedCosineLowerIntegral(double lambda) {
  // L = integral_0^1 mu e^(-lambda (mu + 1)) d mu = e^-lambda (1 - e^-lambda (1 + lambda)) /
  // lambda^2 = e^-lambda sum_k (-lambda)^k (k + 1) / (k + 2)!  (expanding e^-lambda (1 + lambda)).
  if (lambda <= kTaylorSwitch) {
    return std::exp(-lambda) * taylor(lambda, [](int k) {
             return (k % 2 == 0 ? 1.0 : -1.0) * double(k + 1) * inverseFactorial(k + 2);
           });
  }
  const double e = std::exp(-lambda);
  return e * (em1x(-lambda) - e) / lambda;
}

double sgClampedCosineIntegralOverPi(double lambda, double cosine) {
  // [T24] fit constants for t(lambda), section 4.3 option 2.
  constexpr double kA = 2.7360831611272558;
  constexpr double kB = 17.021297781741875;
  constexpr double kC = 4.0100826728510421;
  constexpr double kD = 15.219156263147211;
  constexpr double kE = 76.087896272360737;
  const double c = std::clamp(cosine, -1.0, 1.0);
  // t = lambda sqrt(1/2 (lambda^2 + A lambda + B) / (lambda^3 + C lambda^2 + D lambda + E));
  // above 1 with numerator and denominator divided by lambda^3 (no overflow for huge lambda).
  double t = 0.0;
  if (lambda <= 1.0) {
    t = lambda * std::sqrt(0.5 * ((lambda + kA) * lambda + kB) /
                           (((lambda + kC) * lambda + kD) * lambda + kE));
  } else {
    const double r = 1.0 / lambda;
    t = std::sqrt(lambda) *
        std::sqrt(0.5 * ((kB * r + kA) * r + 1.0) / (((kE * r + kD) * r + kC) * r + 1.0));
  }
  double s = 0.5 + 0.5 * c;
  if (t >= kTinySteepness) {
    // erfc(-t c) and erfc(t) directly (not 1 - erf): no clamp at eps/2 is needed in double.
    s = 0.5 * (c * std::erfc(-t * c) + std::erfc(t)) -
        std::exp(-t * t * c * c) * std::expm1(t * t * (c * c - 1.0)) / (2.0 * std::sqrt(kPi) * t);
  }
  s = std::clamp(s, 0.0, 1.0);
  const double upper = clampedCosineUpperIntegral(lambda);
  const double lower = clampedCosineLowerIntegral(lambda);
  // U and L are per 2 pi; D is per pi, hence the 2 (D(0, c) = 2 * 1/2 = 1, the white furnace).
  return 2.0 * (lower + (upper - lower) * s);
}

VsglIncomingRadiance vsglIncomingRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver) {
  return vsglIncomingRadiance(lobe, receiver, VsglLobeEmission{}, glm::dvec3(0.0));
}

VsglIncomingRadiance vsglIncomingRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver,
                                          const VsglLobeEmission& emission, glm::dvec3 normal) {
  const glm::dvec3 mean(lobe.meanVariance);
  const double variance = lobe.meanVariance.w;
  // The fp32 axis is unit only to ~1e-7, which sharpnesses up to 2^41 would amplify in the
  // product (whose log amplitude assumes unit axes); a zero axis comes with sharpness 0.
  const glm::dvec3 axis = safeNormalize(glm::dvec3(lobe.axisSharpness), {0.0, 0.0, 1.0});
  const double sharpness = lobe.axisSharpness.w;

  const glm::dvec3 toLight = mean - receiver;
  const double distance2 = glm::dot(toLight, toLight);
  const double distance = std::sqrt(distance2);
  // Foreshortening f at the receiver's elevation above the cluster's plane, its cosine measured
  // against sqrt(d^2 + v): h / d far away, h / sqrt(v) inside the cluster, so that a receiver
  // in the plane gets f = 1 - beta however close it is to the mean.
  const double reach = std::sqrt(distance2 + variance);
  const double foreshortening =
      emission.flatness +
      (reach > 0.0 ? std::max(-glm::dot(emission.plane, toLight), 0.0) / reach : 0.0);
  const double spotVariance =
      std::max({foreshortening * variance, distance2 * kVarianceFloorScale, kMinVariance});
  // The planar Gaussian spot seen from the receiver, G(w; l / d, d^2 / v_f) (section 4.1). At
  // d = 0 its sharpness is 0 and its axis irrelevant (section 12 case 12).
  const Sg spot{distance > 0.0 ? toLight / distance : -axis, distance2 / spotVariance, 0.0};

  double emissionSharpness = sharpness;
  double normalisation =
      emission.normalisation < 0.0 ? sgIntegral(sharpness) : emission.normalisation;
  double keep = 1.0;
  if (emission.lambertian) {
    const double beta = 1.0 - emission.flatness;
    const double near = sharpness / std::max(sharpness + spot.sharpness, kMinVariance);
    emissionSharpness = emission.flatness * sharpness + beta * sharpness * near;
    normalisation = emission.flatness * sgIntegral(emissionSharpness) +
                    beta * 2.0 * kPi * clampedCosineUpperIntegral(emissionSharpness);
    keep = 1.0 - near * std::max(glm::dot(emission.plane, normal), 0.0);
  }
  // Emitted SG over incident directions (they point back along -xi), times the spot.
  const Sg emitted{-axis, emissionSharpness, 0.0};

  VsglIncomingRadiance radiance;
  radiance.sg = sgProduct(emitted, spot);
  // E = Phi f / (2 pi v_f N) (section 3.4 with N for S): 2-D Gaussian times the emission's
  // normalisation, so that the spot's integral 2 pi v_f / d^2 leaves I(-w_l) / d^2.
  radiance.scale =
      glm::dvec3(lobe.power) * (keep * foreshortening / (2.0 * kPi * spotVariance * normalisation));
  return radiance;
}

glm::dvec3 vsglDiffuseRadiance(const gpu::VsglLobe& lobe, glm::dvec3 receiver, glm::dvec3 normal,
                               glm::dvec3 albedo) {
  const VsglIncomingRadiance radiance = vsglIncomingRadiance(lobe, receiver);
  const double d =
      sgClampedCosineIntegralOverPi(radiance.sg.sharpness, glm::dot(radiance.sg.axis, normal));
  return albedo * radiance.scale * (std::exp(radiance.sg.logAmplitude) * d);
}

// ---------------------------------------------------------------------------------------------
// Glossy (section 4.4).

namespace {

// kGgxAlbedo[i][j] = (albedo at f0 = 0, albedo at f0 = 1) of brdf.glsl's specular lobe at
// n . v = max((i / 16)^2, kSgGgxMinViewCosine) and alpha = max((j / 16)^2, kSgGgxMinAlpha), by
// the half-vector quadrature of tests/unit/test_sg_math.cpp (albedoQuadrature with every panel
// divided by 8: converged to < 1e-7; printed to 6 decimals). The square roots spread the nodes
// where the albedo bends: grazing views and smooth surfaces. The GLSL port reads these numbers from
// a storage buffer the host fills with ggxSpecularAlbedoNode (a constant GLSL array indexed at run
// time is rebuilt per invocation on lavapipe).
// clang-format off
constexpr double kGgxAlbedo[kGgxAlbedoTableSize * kGgxAlbedoTableSize][2] = {
    // sqrt(n.v) = 0/16
    {0.953920, 0.979641}, {0.914994, 0.994640}, {0.780871, 0.998643}, {0.638754, 0.999376},
    {0.510020, 0.999616}, {0.401540, 0.999708}, {0.314057, 0.999736}, {0.245523, 0.999731},
    {0.192860, 0.999703}, {0.152891, 0.999659}, {0.122769, 0.999603}, {0.100135, 0.999537},
    {0.083123, 0.999460}, {0.070300, 0.999376}, {0.060591, 0.999284}, {0.053194, 0.999185},
    {0.047521, 0.999079},
    // sqrt(n.v) = 1/16
    {0.939545, 0.963100}, {0.834782, 0.892062}, {0.754258, 0.952450}, {0.628577, 0.977063},
    {0.504363, 0.986200}, {0.397493, 0.990120}, {0.310772, 0.991782}, {0.242698, 0.992256},
    {0.190352, 0.992001}, {0.150607, 0.991243}, {0.120637, 0.990106}, {0.098094, 0.988668},
    {0.081122, 0.986977}, {0.068298, 0.985072}, {0.058553, 0.982980}, {0.051092, 0.980724},
    {0.045331, 0.978324},
    // sqrt(n.v) = 2/16
    {0.920820, 0.997723}, {0.876992, 0.964541}, {0.715301, 0.891861}, {0.601126, 0.924239},
    {0.487329, 0.950474}, {0.385222, 0.964285}, {0.300985, 0.971002}, {0.234485, 0.973641},
    {0.183267, 0.973710}, {0.144364, 0.972009}, {0.115022, 0.968997}, {0.092933, 0.964960},
    {0.076275, 0.960093}, {0.063651, 0.954539}, {0.054014, 0.948411}, {0.046591, 0.941798},
    {0.040812, 0.934773},
    // sqrt(n.v) = 3/16
    {0.835218, 0.999576}, {0.823576, 0.992736}, {0.709315, 0.922009}, {0.572635, 0.890993},
    {0.461742, 0.909888}, {0.365339, 0.929903}, {0.285127, 0.942210}, {0.221418, 0.947991},
    {0.172250, 0.949059}, {0.134903, 0.946700}, {0.106749, 0.941755}, {0.085562, 0.934793},
    {0.069577, 0.926219}, {0.057446, 0.916339}, {0.048164, 0.905395}, {0.040988, 0.893588},
    {0.035374, 0.881084},
    // sqrt(n.v) = 4/16
    {0.723814, 0.999868}, {0.719327, 0.997826}, {0.663783, 0.964366}, {0.544353, 0.904872},
    {0.431626, 0.888677}, {0.339175, 0.899114}, {0.263798, 0.911728}, {0.204023, 0.919277},
    {0.157869, 0.921151}, {0.122829, 0.918196}, {0.096445, 0.911351}, {0.076615, 0.901392},
    {0.061669, 0.888938}, {0.050332, 0.874487}, {0.041656, 0.858447}, {0.034945, 0.841162},
    {0.029691, 0.822924},
    // sqrt(n.v) = 5/16
    {0.598038, 0.999946}, {0.595967, 0.999137}, {0.569777, 0.984484}, {0.492943, 0.937630},
    {0.394257, 0.895672}, {0.307582, 0.883850}, {0.237815, 0.887352}, {0.182992, 0.892276},
    {0.140781, 0.893216}, {0.108781, 0.889040}, {0.084725, 0.880077}, {0.066679, 0.867031},
    {0.053104, 0.850633}, {0.042827, 0.831553}, {0.034978, 0.810379}, {0.028918, 0.787622},
    {0.024183, 0.763723},
    // sqrt(n.v) = 6/16
    {0.468633, 0.999974}, {0.467633, 0.999588}, {0.455013, 0.992599}, {0.412697, 0.963607},
    {0.342385, 0.918726}, {0.269329, 0.887348}, {0.207704, 0.875192}, {0.159089, 0.871820},
    {0.121723, 0.868615}, {0.093435, 0.861665}, {0.072199, 0.849890}, {0.056299, 0.833460},
    {0.044366, 0.813005}, {0.035358, 0.789281}, {0.028499, 0.763035}, {0.023224, 0.734953},
    {0.019121, 0.705639},
    // sqrt(n.v) = 7/16
    {0.345623, 0.999986}, {0.345163, 0.999777}, {0.339251, 0.996065}, {0.318013, 0.978993},
    {0.275924, 0.942951}, {0.223177, 0.903576}, {0.173672, 0.876532}, {0.133051, 0.861169},
    {0.101469, 0.850304}, {0.077480, 0.838327}, {0.059458, 0.822509}, {0.045972, 0.802084},
    {0.035869, 0.777303}, {0.028262, 0.748867}, {0.022493, 0.717622}, {0.018076, 0.684414},
    {0.014661, 0.650015},
    // sqrt(n.v) = 8/16
    {0.237290, 0.999991}, {0.237110, 0.999867}, {0.234654, 0.997700}, {0.225128, 0.987395},
    {0.203536, 0.961567}, {0.171364, 0.923938}, {0.136619, 0.888043}, {0.105738, 0.860844},
    {0.080828, 0.840082}, {0.061601, 0.820821}, {0.047053, 0.799387}, {0.036133, 0.774040},
    {0.027948, 0.744456}, {0.021796, 0.711125}, {0.017144, 0.674906}, {0.013600, 0.636768},
    {0.010876, 0.597641},
    // sqrt(n.v) = 9/16
    {0.149273, 0.999994}, {0.149232, 0.999915}, {0.148506, 0.998545}, {0.145097, 0.992004},
    {0.135951, 0.974080}, {0.119694, 0.942579}, {0.099073, 0.904569}, {0.078499, 0.868868},
    {0.060719, 0.838151}, {0.046475, 0.810156}, {0.035481, 0.781592}, {0.027142, 0.750209},
    {0.020860, 0.715146}, {0.016130, 0.676592}, {0.012559, 0.635339}, {0.009848, 0.592429},
    {0.007777, 0.548921},
    // sqrt(n.v) = 10/16
    {0.084030, 0.999996}, {0.084046, 0.999942}, {0.084081, 0.999016}, {0.083535, 0.994627},
    {0.080900, 0.982076}, {0.074612, 0.957260}, {0.064766, 0.921735}, {0.053278, 0.882024},
    {0.042235, 0.843284}, {0.032778, 0.806401}, {0.025183, 0.769687}, {0.019285, 0.731193},
    {0.014780, 0.689849}, {0.011365, 0.645605}, {0.008780, 0.599155}, {0.006820, 0.551570},
    {0.005328, 0.504000},
    // sqrt(n.v) = 11/16
    {0.040785, 0.999997}, {0.040815, 0.999958}, {0.041078, 0.999295}, {0.041566, 0.996186},
    {0.041686, 0.987147}, {0.040429, 0.967967}, {0.037142, 0.936986}, {0.032174, 0.897168},
    {0.026537, 0.853415}, {0.021156, 0.808777}, {0.016522, 0.763680}, {0.012761, 0.717285},
    {0.009808, 0.668853}, {0.007533, 0.618350}, {0.005794, 0.566436}, {0.004471, 0.514200},
    {0.003465, 0.462848},
    // sqrt(n.v) = 12/16
    {0.016031, 0.999998}, {0.016054, 0.999968}, {0.016291, 0.999469}, {0.016889, 0.997155},
    {0.017701, 0.990404}, {0.018247, 0.975505}, {0.017974, 0.949390}, {0.016661, 0.911995},
    {0.014553, 0.866317}, {0.012117, 0.815947}, {0.009753, 0.763082}, {0.007680, 0.708461},
    {0.005970, 0.652271}, {0.004609, 0.594894}, {0.003548, 0.537159}, {0.002732, 0.480222},
    {0.002108, 0.425321},
    // sqrt(n.v) = 13/16
    {0.004534, 0.999998}, {0.004547, 0.999975}, {0.004677, 0.999583}, {0.005047, 0.997782},
    {0.005664, 0.992544}, {0.006371, 0.980757}, {0.006894, 0.958981}, {0.006996, 0.925200},
    {0.006615, 0.880087}, {0.005873, 0.826356}, {0.004962, 0.767037}, {0.004045, 0.704414},
    {0.003218, 0.640045}, {0.002522, 0.575213}, {0.001959, 0.511233}, {0.001514, 0.449474},
    {0.001169, 0.391210},
    // sqrt(n.v) = 14/16
    {0.000708, 0.999999}, {0.000711, 0.999979}, {0.000756, 0.999659}, {0.000892, 0.998201},
    {0.001150, 0.993986}, {0.001505, 0.984428}, {0.001878, 0.966204}, {0.002164, 0.936290},
    {0.002282, 0.893376}, {0.002219, 0.838518}, {0.002015, 0.774491}, {0.001736, 0.704613},
    {0.001440, 0.631970}, {0.001162, 0.559200}, {0.000921, 0.488523}, {0.000723, 0.421756},
    {0.000563, 0.360269},
    // sqrt(n.v) = 15/16
    {0.000026, 0.999999}, {0.000027, 0.999982}, {0.000033, 0.999712}, {0.000057, 0.998490},
    {0.000107, 0.994983}, {0.000190, 0.987022}, {0.000296, 0.971584}, {0.000406, 0.945268},
    {0.000495, 0.905397}, {0.000544, 0.851208}, {0.000548, 0.784349}, {0.000515, 0.708379},
    {0.000457, 0.627721}, {0.000390, 0.546686}, {0.000322, 0.468863}, {0.000261, 0.396851},
    {0.000209, 0.332236},
    // sqrt(n.v) = 16/16
    {0.000000, 0.999999}, {0.000000, 0.999985}, {0.000000, 0.999750}, {0.000001, 0.998695},
    {0.000003, 0.995688}, {0.000007, 0.988884}, {0.000012, 0.975587}, {0.000019, 0.952385},
    {0.000027, 0.915812}, {0.000035, 0.863535}, {0.000042, 0.795599}, {0.000046, 0.714964},
    {0.000048, 0.626886}, {0.000046, 0.537452}, {0.000043, 0.452070}, {0.000039, 0.374539},
    {0.000034, 0.306853},
};
// clang-format on

// Weight of the sharp-light terms, w = lambda / (lambda + lambda_r + kWideLightBias): the
// bias keeps w small for a wide light on a rough surface (lambda_r -> 0 as alpha -> 1), where
// the tabulated albedo, not the light's own direction, sets the mean of f cos / p (Fresnel
// included). Chosen by the measured error: with 0 instead of 2 the worst alpha = 1 error at
// n . v >= 0.3 grows from 20 % to 127 % (SgMathGlossy.MatchesQuadrature, lambda = 0.1, f0 = 0.04).
constexpr double kWideLightBias = 2.0;
// Length of the view's tangential part below which the view counts as normal incidence.
constexpr double kSgGgxMinTangential = 1e-4;
// FLT_MIN, the floor of the logarithms below (the GLSL port uses the same).
constexpr double kFltMin = 0x1p-126;
// Abramowitz and Stegun 5.1.53: E1(x) + ln x for 0 < x <= 1, |error| < 2e-7.
constexpr double kE1Series[6] = {-0.57721566, 0.99999193,  -0.24991055,
                                 0.05519968,  -0.00976004, 0.00107857};
// Abramowitz and Stegun 5.1.54: x e^x E1(x) = P(x) / Q(x) for x >= 1, |error| < 2e-8, with
// monic quartics P and Q (coefficients of x^3 .. x^0).
constexpr double kE1P[4] = {8.5733287401, 18.0590169730, 8.6347608925, 0.2677737343};
constexpr double kE1Q[4] = {9.5733223454, 25.6329561486, 21.0996530827, 3.9584969228};

// The GGX smith term of the reflection pdf, s(c) = sqrt(alpha^2 + (1 - alpha^2) c^2) (the
// projected area of the unit-height GGX ellipsoid seen at cosine c; 2 s / (c + s) is G1).
double ggxProjectedArea(double alpha2, double cosine) {
  return std::sqrt(alpha2 + (1.0 - alpha2) * cosine * cosine);
}

// Schlick's Fresnel with F90, as brdf.glsl.
glm::dvec3 schlickFresnel(glm::dvec3 f0, double f90, double cosine) {
  const double m = 1.0 - std::max(cosine, 0.0);
  const double m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

// The mean over an SG lobe (axis, sharpness; unnormalised) of f_spec cos / p without Fresnel,
//   W(c) = 2 c s_v / (c s_v + n_v s(c)),  c = w . n > 0, s_v = s(n_v)
// (brdf.glsl's D Vis c over the pdf D / (4 s_v)), as W(c) = c g(c): the clamped-cosine mean
// E[c^+] = pi D(lambda, axis_z) / S(lambda) ([T24], section 4.3) times g at the mean cosine of
// the part above the horizon, E[c^+] / P(c > 0) (P the vMF upper fraction, section 4.2), which
// is returned in `upperCosine`.
double ggxVisibilityRatioMean(double sharpness, double axisCosine, double nv, double alpha2,
                              double& upperCosine) {
  const double meanCosine =
      kPi * sgClampedCosineIntegralOverPi(sharpness, axisCosine) / sgIntegral(sharpness);
  const double upper = vmfUpperHemisphereFraction(sharpness, axisCosine);
  const double c = upper > 0.0 ? std::clamp(meanCosine / upper, 0.0, 1.0) : 0.0;
  upperCosine = c;
  const double sv = ggxProjectedArea(alpha2, nv);
  return meanCosine * 2.0 * sv / (c * sv + nv * ggxProjectedArea(alpha2, c));
}

}  // namespace

double sgGgxPeakCorrection(double beta) {
  if (!(beta > 0.0)) return 1.0;  // beta = 0: the lobe is only the light
  if (beta > 100.0) {
    // Asymptotic series: 1 - 1/beta + 4/beta^2 - 18/beta^3 + 96/beta^4 (truncation < 1e-7).
    const double y = 1.0 / beta;
    return 1.0 + y * (-1.0 + y * (4.0 + y * (-18.0 + y * 96.0)));
  }
  double kappa = 0.0;  // 1 - beta e^beta E1(beta)
  if (beta <= 1.0) {
    double poly = 0.0;
    for (int k = 5; k >= 0; --k) poly = poly * beta + kE1Series[k];
    kappa = 1.0 - beta * std::exp(beta) * (poly - std::log(beta));
  } else {
    // 1 - P/Q = (Q - P) / Q, differences of the coefficients: no cancellation as P/Q -> 1.
    double q = 1.0, d = 0.0;
    for (int k = 0; k < 4; ++k) {
      q = q * beta + kE1Q[k];
      d = d * beta + (kE1Q[k] - kE1P[k]);
    }
    kappa = d / q;
  }
  return kappa * (1.0 + beta);
}

glm::dvec2 ggxSpecularAlbedoNode(int i, int j) {
  const double* a = kGgxAlbedo[i * kGgxAlbedoTableSize + j];
  return {a[0], a[1]};
}

glm::dvec2 ggxSpecularAlbedo(double nv, double alpha) {
  const double last = double(kGgxAlbedoTableSize - 1);
  const double u = std::sqrt(std::clamp(nv, kSgGgxMinViewCosine, 1.0)) * last;
  const double t = std::sqrt(std::clamp(alpha, kSgGgxMinAlpha, 1.0)) * last;
  const int i = std::min(int(u), kGgxAlbedoTableSize - 2),
            j = std::min(int(t), kGgxAlbedoTableSize - 2);
  const double fu = u - double(i), ft = t - double(j);
  return glm::mix(
      glm::mix(ggxSpecularAlbedoNode(i, j), ggxSpecularAlbedoNode(i, j + 1), ft),
      glm::mix(ggxSpecularAlbedoNode(i + 1, j), ggxSpecularAlbedoNode(i + 1, j + 1), ft), fu);
}

SgGgxReceiver sgGgxReceiver(glm::dvec3 normal, glm::dvec3 view, double alpha, glm::dvec3 f0,
                            double f90) {
  SgGgxReceiver r;
  r.normal = normal;
  r.f0 = f0;
  r.f90 = f90;
  const double a = std::clamp(alpha, kSgGgxMinAlpha, 1.0);
  r.alpha2 = a * a;

  // View frame (x along the view's tangential part, z = n): the filtered NDF below is diagonal
  // in it. n . v is clamped like brdf.glsl, and the view rebuilt at that cosine.
  r.nv = std::max(glm::dot(normal, view), kSgGgxMinViewCosine);
  const glm::dvec3 tangential = view - glm::dot(normal, view) * normal;
  const double tangentialLength = glm::length(tangential);
  if (tangentialLength > kSgGgxMinTangential) {
    r.ex = tangential / tangentialLength;
  } else {
    // Within 1e-4 rad of the normal (or of its opposite) the azimuth of the view is lost to
    // rounding (in fp32 first) and the lobe is isotropic to O(1e-8): any tangent will do.
    const glm::dvec3 helper =
        std::abs(normal.x) < 0.6 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    r.ex = glm::normalize(glm::cross(helper, normal));
  }
  r.ey = glm::cross(normal, r.ex);
  r.wo = glm::dvec3(std::sqrt(std::max(1.0 - r.nv * r.nv, 0.0)), 0.0, r.nv);

  // Dominant reflection direction: the mirror image of the view about the dominant visible
  // normal, the centre of the GGX spherical-cap VNDF (Dupuy and Benyoub 2023, as
  // GGXDominantVisibleNormal in [R]; n . v > 0 here, so the plain form is stable).
  const double t = std::sqrt(r.alpha2 * r.wo.x * r.wo.x + r.nv * r.nv);
  const glm::dvec3 dominantNormal = glm::normalize(glm::dvec3(r.alpha2 * r.wo.x, 0.0, t + r.nv));
  r.dominantReflection = 2.0 * glm::dot(r.wo, dominantNormal) * dominantNormal - r.wo;
  // Reflection SG sharpness (1 - alpha^2) / (2 alpha^2) ([R]'s "conservative" sharpness): the
  // NDF as an SG of sharpness 2 / alpha^2 - 2 ([TH19]) mapped to reflection directions with the
  // in-plane Jacobian 1/4. Its normalised peak equals the GGX reflection pdf's peak at normal
  // incidence for small alpha. q = 1 / (projected roughness) = (1 - alpha^2) / alpha^2.
  r.q = (1.0 - r.alpha2) / r.alpha2;
  r.reflectionSharpness = 0.5 * r.q;

  // The wide-light end of E (see sgGgxReflection): the tabulated albedo A(f0) over the model's
  // own value W_0 for a constant light (the reflection SG alone), as a logarithm with an FLT_MIN
  // floor: A can be 0 (f0 = 0 at normal incidence), where the factor is 0 either way; the floor
  // keeps 0^0 out of the w = 0 limit.
  double upperCosineWide = 0.0;
  const double ratioWide = ggxVisibilityRatioMean(r.reflectionSharpness, r.dominantReflection.z,
                                                  r.nv, r.alpha2, upperCosineWide);
  const glm::dvec2 table = ggxSpecularAlbedo(r.nv, a);
  // A = F90 x + F0 (y - x): Schlick's F0 + (F90 - F0) s integrated against the table's two
  // moments (x: of s alone, y: of 1).
  const glm::dvec3 albedo = f90 * table.x + f0 * (table.y - table.x);
  for (int c = 0; c < 3; ++c) {
    r.logWideFactor[c] = std::log(std::max(albedo[c], kFltMin) / std::max(ratioWide, kFltMin));
  }
  return r;
}

glm::dvec3 sgGgxReflection(const Sg& light, const SgGgxReceiver& r) {
  const double lambda = std::max(light.sharpness, 0.0);
  const double nv = r.nv, q = r.q;
  const glm::dvec3 wo = r.wo;
  const glm::dvec3 xi(glm::dot(light.axis, r.ex), glm::dot(light.axis, r.ey),
                      glm::dot(light.axis, r.normal));

  // K, sharp-light part: [T24] Section 5.2 NDF filtering. In projected space the GGX has the
  // variance-like matrix p I (p = alpha^2 / (1 - alpha^2), [TK21] Eq. 4), the light adds
  // 2 sigma^2 J J^T with sigma^2 = 1 / lambda and J = R diag(1/2, 1/(2 n_v)) the half-vector ->
  // reflection Jacobian at h = n; in the view frame everything is diagonal, so [T24]'s return
  // to slope space, (S + det S I) / (1 + tr S + det S), is exactly S_ii / (1 + S_ii). Written
  // with lambda q S_ii = b_i (finite for lambda = 0 and alpha = 1, no overflow up to 2^41):
  //   b = (lambda + q/2, lambda + q / (2 n_v^2)),  m_i = b_i / (lambda q + b_i).
  const double lq = lambda * q;
  const double b1 = lambda + 0.5 * q, b2 = lambda + 0.5 * q / (nv * nv);
  const double m1 = lq + b1 > 0.0 ? b1 / (lq + b1) : 1.0;
  const double m2 = lq + b2 > 0.0 ? b2 / (lq + b2) : 1.0;
  // Reflection pdf of the symmetric GGX with roughness matrix diag(m1, m2) at the half vector
  // of the view and the light axis ([R] SGGXReflectionPDF): D(h) / (4 sqrt(m1 wo_x^2 + nv^2)).
  const glm::dvec3 halfSum = wo + xi;
  const double halfLength = glm::length(halfSum);
  const glm::dvec3 h = halfLength > 0.0 ? halfSum / halfLength : glm::dvec3(0.0, 0.0, 1.0);
  const double stretched = h.x * h.x / m1 + h.y * h.y / m2 + h.z * h.z;
  const double ndf = 1.0 / (kPi * std::sqrt(m1 * m2) * stretched * stretched);
  const double filteredPdf = ndf / (4.0 * std::sqrt(m1 * wo.x * wo.x + nv * nv));
  const double sharpMass = sgIntegral(lambda) * filteredPdf;

  // K, wide-light part: the light times the normalised reflection SG, an exact SG inner product
  // (section 4.2) divided by S(lambda_r).
  const Sg unitLight{xi, lambda, 0.0};
  const Sg reflection{r.dominantReflection, r.reflectionSharpness, 0.0};
  const Sg product = sgProduct(unitLight, reflection);
  const double wideMass = std::exp(product.logAmplitude) * sgIntegral(product.sharpness) /
                          sgIntegral(r.reflectionSharpness);

  // Both parts predict 1 / (1 + beta) for the peak of a small-angle GGX lobe convolved with the
  // light, beta = lambda / (2 lambda_r) = lambda alpha^2 / (1 - alpha^2); the exact t x Gaussian
  // peak is (1 - beta e^beta E1(beta)), hence the correction (up to -19 %).
  const double w = lambda / (lambda + r.reflectionSharpness + kWideLightBias);
  const double beta = q > 0.0 ? lambda / q : std::numeric_limits<double>::infinity();
  const double mass = sgGgxPeakCorrection(beta) * (w * sharpMass + (1.0 - w) * wideMass);

  // E: the mean W_q of f cos / p over the product lobe without Fresnel, Fresnel F_q at the half
  // vector of the lobe's lit part (below), and the same model's W_0 for a constant light (the
  // reflection SG alone), whose ratio to the tabulated albedo A(f0) corrects the model as the
  // light widens (r.logWideFactor):
  //   E = W_q F_q^w (A(f0) / W_0)^(1 - w),
  // exact for a constant light (w = 0: E = A) and, for a sharp light (w -> 1), the visibility
  // ratio and Fresnel at the light direction. (A geometric rather than linear blend: measured
  // better for f0 = 0.04, where F_q and A / W_0 differ by up to 10x.)
  double upperCosine = 0.0;
  const double ratio =
      ggxVisibilityRatioMean(product.sharpness, product.axis.z, nv, r.alpha2, upperCosine);
  // Fresnel direction: the product axis raised (or lowered) to the mean cosine of its part above
  // the horizon, at the axis' azimuth. F varies fastest at grazing half vectors, i.e. for the
  // lobes the horizon cuts; the unlit part below must not set it. A sharp light above the
  // horizon keeps its own direction (upperCosine -> axis_z).
  const double horizontal = std::hypot(product.axis.x, product.axis.y);
  const double sine = std::sqrt(std::max(1.0 - upperCosine * upperCosine, 0.0));
  const glm::dvec3 fresnelAxis = horizontal > 0.0
                                     ? glm::dvec3(product.axis.x / horizontal * sine,
                                                  product.axis.y / horizontal * sine, upperCosine)
                                     : glm::dvec3(0.0, 0.0, 1.0);
  const glm::dvec3 lobeHalf = wo + fresnelAxis;
  const double lobeHalfLength = glm::length(lobeHalf);
  const double vh = lobeHalfLength > 0.0 ? glm::dot(wo, lobeHalf) / lobeHalfLength : 0.0;
  const glm::dvec3 fresnel = schlickFresnel(r.f0, r.f90, vh);
  glm::dvec3 result(0.0);
  for (int c = 0; c < 3; ++c) {
    // The FLT_MIN floor as in logWideFactor: F is 0 where f0 = 0 at normal incidence.
    const double logE =
        w * std::log(std::max(fresnel[c], kFltMin)) + (1.0 - w) * r.logWideFactor[c];
    result[c] = mass * ratio * std::exp(logE);
  }
  return result;
}

glm::dvec3 sgGgxReflection(const Sg& light, glm::dvec3 normal, glm::dvec3 view, double alpha,
                           glm::dvec3 f0, double f90) {
  return sgGgxReflection(light, sgGgxReceiver(normal, view, alpha, f0, f90));
}

}  // namespace gi
