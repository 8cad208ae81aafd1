// The numerical-stability suite, SG functions on the GPU: the hard inputs of vsgl-math.md
// section 12 (cases 7-13, 15 and 18) run through the fp32 functions of shaders/common that the
// passes use (via the probe shaders/probe/sg_probe.comp) and held against the double oracles of
// gi/src/reference. Every output must be finite; each test states the documented value or
// bound it asserts and why its tolerance is what it is. The CPU side of each case lives in
// tests/unit (docs/techniques/stability.md maps case -> tests).
//
// Tolerances, from fp32 arithmetic on lavapipe (LLVM's exp, log, sqrt and trigonometry are
// correctly rounded to within a few ulp, u = 2^-24 = 6e-8):
// - kFew = 1e-6 relative: a formula of a handful of roundings and one exp or log (<= 16 u);
//   also the section-12 bound on the jump at a branch switch.
// - kChain = 1e-5 relative: a chain of tens of operations with erf/erfc fits (the [NR92] fit
//   itself is good to 1.2e-7) whose cancellations cost a few bits.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/buffer.h"
#include "engine/commands.h"
#include "engine/program.h"
#include "gpu_fixture.h"
#include "reference/sg_math.h"
#include "reference/vsgl_bound.h"
#include "reference/vsgl_sampling.h"
#include "shared/sg_probe.h"
#include "shared/vsgl.h"
#include "spirv/sg_probe.h"

namespace {

constexpr double kFew = 1e-6;
constexpr double kChain = 1e-5;
constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxSharpness = VSGL_MAX_SHARPNESS;  // 2^41

gpu::SgProbeCase probe(uint32_t function, glm::vec4 a, glm::vec4 b = {}, glm::vec4 c = {}) {
  gpu::SgProbeCase p{};
  p.a = a;
  p.b = b;
  p.c = c;
  p.function = function;
  return p;
}

bool finite(const gpu::SgProbeResult& r) {
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(r.x[k]) || !std::isfinite(r.y[k])) return false;
  return true;
}

// |gpu - ref| <= tolerance max(|ref|, floor): relative, with an absolute floor for values that
// are 0 in exact arithmetic.
void expectNear(double gpu, double ref, double tolerance, double floor, const std::string& what) {
  EXPECT_TRUE(std::isfinite(gpu)) << what;
  EXPECT_LE(std::abs(gpu - ref), tolerance * std::max(std::abs(ref), floor))
      << what << ": gpu " << gpu << ", reference " << ref;
}

class StabilitySg : public testing_gpu::GpuTest {
 protected:
  void SetUp() override {
    testing_gpu::GpuTest::SetUp();
    if (IsSkipped()) return;
    std::vector<glm::vec2> table;
    for (int i = 0; i < gi::kGgxAlbedoTableSize; ++i)
      for (int j = 0; j < gi::kGgxAlbedoTableSize; ++j)
        table.emplace_back(gi::ggxSpecularAlbedoNode(i, j));
    albedo_ = engine::Buffer(ctx(), table.size() * sizeof(glm::vec2),
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::Upload);
    albedo_.upload(ctx(), std::span<const glm::vec2>(table));
  }

  // Runs every case through the probe; every output must be finite.
  std::vector<gpu::SgProbeResult> run(const std::vector<gpu::SgProbeCase>& cases) {
    const auto count = static_cast<uint32_t>(cases.size());
    engine::Buffer in(ctx(), cases.size() * sizeof(gpu::SgProbeCase),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::Upload);
    in.upload(ctx(), std::span<const gpu::SgProbeCase>(cases));
    engine::Buffer out(ctx(), cases.size() * sizeof(gpu::SgProbeResult),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
    engine::ComputeProgram program(
        ctx(), "sg_probe", kSgProbeSpv,
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        sizeof(gpu::SgProbePush));
    const gpu::SgProbePush push{count, 0, 0, 0};
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      program.dispatch(cmd,
                       {engine::Binding::storage(in), engine::Binding::storage(out),
                        engine::Binding::storage(albedo_)},
                       push, engine::groupCount(count, SG_PROBE_GROUP));
    });
    std::vector<gpu::SgProbeResult> results = out.readbackAs<gpu::SgProbeResult>(ctx());
    for (size_t i = 0; i < cases.size(); ++i)
      EXPECT_TRUE(finite(results[i]))
          << "case " << i << " (function " << cases[i].function << ") is not finite";
    return results;
  }

 private:
  engine::Buffer albedo_;
};

// Case 7: a zero mean axis (opposing normals) gives an isotropic lobe, lambda = 0 and S = 4 pi;
// a unit one (one VPL) the clamp 2^41, never infinity; r = NaN or <= 0 gives 0. Banerjee's
// estimate round-trips through its inverse to within what fp32 can hold: r sits within
// 1 / lambda of 1, where its spacing 2^-24 moves kappa ~ 2 / (1 - r) by lambda 2^-23
// relative, hence the bound 4 lambda u + kChain, tested to lambda = 1e6 as section 12 says.
TEST_F(StabilitySg, AxisLengthZeroAndOne) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float belowOne = std::nextafter(1.0f, 0.0f);
  auto r =
      run({probe(SG_PROBE_MEAN_AXIS, {0, 0, 0, 0}), probe(SG_PROBE_BANERJEE, {1.0f, 0, 0, 0}),
           probe(SG_PROBE_BANERJEE, {belowOne, 0, 0, 0}), probe(SG_PROBE_BANERJEE, {0.0f, 0, 0, 0}),
           probe(SG_PROBE_BANERJEE, {-0.5f, 0, 0, 0}), probe(SG_PROBE_BANERJEE, {nan, 0, 0, 0}),
           probe(SG_PROBE_MEAN_AXIS, {0, 0, 2.0f, 0}), probe(SG_PROBE_INTEGRAL, {0, 0, 0, 0})});
  EXPECT_EQ(r[0].x, glm::vec4(0, 0, 1, 0));
  EXPECT_EQ(r[1].x.x, float(kMaxSharpness));
  expectNear(r[2].x.x, gi::banerjeeSharpness(belowOne), kFew, 0.0, "kappa(1 - ulp)");
  EXPECT_LE(r[2].x.x, float(kMaxSharpness));
  EXPECT_EQ(r[3].x.x, 0.0f);
  EXPECT_EQ(r[4].x.x, 0.0f);
  EXPECT_EQ(r[5].x.x, 0.0f);
  EXPECT_EQ(r[6].x, glm::vec4(0, 0, 1, float(kMaxSharpness)));  // axis sums longer than 1
  expectNear(r[7].x.x, 4.0 * kPi, kFew, 0.0, "S(0)");

  std::vector<gpu::SgProbeCase> trips;
  const std::vector<double> lambdas = {1e-3, 0.1, 1.0, 10.0, 63.9, 64.1, 1e3, 1e5, 1e6};
  for (double l : lambdas) trips.push_back(probe(SG_PROBE_BANERJEE, {0, float(l), 0, 0}));
  auto lengths = run(trips);
  std::vector<gpu::SgProbeCase> back;
  for (const auto& t : lengths) back.push_back(probe(SG_PROBE_BANERJEE, {t.x.y, 0, 0, 0}));
  auto kappas = run(back);
  const double u = std::ldexp(1.0, -24);
  for (size_t i = 0; i < lambdas.size(); ++i) {
    const double l = lambdas[i];
    expectNear(lengths[i].x.y, gi::banerjeeMeanLength(l), kChain, 0.0,
               "r(" + std::to_string(l) + ")");
    expectNear(kappas[i].x.x, l, 4.0 * l * u + kChain, 0.0, "kappa(r(" + std::to_string(l) + "))");
  }
}

// Case 8: identical axes give l_p = 0 exactly and lambda_p = l1 + l2; opposite axes
// l_p = -2 min(l1, l2) and lambda_p = |l1 - l2|, and equal opposite ones lambda_p = 0 with a
// unit axis, not NaN, up to lambda = 2^41. The product's inner-product integral stays finite.
TEST_F(StabilitySg, ProductOfIdenticalAndOppositeAxes) {
  const std::vector<double> lambdas = {0.0, 1e-8, 1.0, 1e3, kMaxSharpness};
  const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  std::vector<gpu::SgProbeCase> cases;
  for (double a : lambdas)
    for (double b : lambdas)
      for (float sign : {1.0f, -1.0f})
        cases.push_back(probe(SG_PROBE_PRODUCT, {axis, float(a)}, {sign * axis, float(b)}));
  auto r = run(cases);
  for (size_t i = 0; i < cases.size(); ++i) {
    const gpu::SgProbeCase& c = cases[i];
    const double a = c.a.w, b = c.b.w;
    const bool opposite = c.b.x != c.a.x;
    const std::string what = std::string(opposite ? "opposite" : "identical") + " axes, lambdas " +
                             std::to_string(a) + ", " + std::to_string(b);
    const gi::Sg ref = gi::sgProduct({glm::dvec3(c.a), a, 0.0}, {glm::dvec3(c.b), b, 0.0});
    // The float inputs are the oracle's: only the probe's own rounding separates the two.
    expectNear(r[i].x.w, ref.sharpness, kFew, 0.0, what + ": lambda_p");
    expectNear(r[i].y.x, ref.logAmplitude, kFew, 0.0, what + ": l_p");
    if (opposite) {
      expectNear(r[i].y.x, -2.0 * std::min(a, b), kFew, 0.0, what + ": -2 min");
    } else {
      EXPECT_EQ(r[i].y.x, 0.0f) << what;
    }
    EXPECT_NEAR(glm::length(glm::vec3(r[i].x)), 1.0f, 1e-6f) << what << ": unit axis";
  }
}

// Case 9: em1x, S, U and L from lambda -> 0 to 2^41, against the oracle; across each branch
// switch (em1x at |x| = 1, S at lambda = 8, U and L at 0.5) the jump between the last float
// on one side and the first on the other is below 1e-6 relative (section 12); S(1e-8) = 4 pi
// and S(2^41) = 2 pi / 2^41, not 0 or NaN.
TEST_F(StabilitySg, SharpnessToZeroAndInfinity) {
  std::vector<double> xs = {0.0,
                            1e-30,
                            -1e-30,
                            1e-7,
                            -1e-7,
                            0.5,
                            -0.5,
                            1.0,
                            -1.0,
                            -20.0,
                            -88.0,
                            -1e4,
                            -2.0 * kMaxSharpness,
                            20.0,
                            80.0};
  for (float edge : {1.0f, -1.0f}) {
    xs.push_back(std::nextafter(edge, 0.0f));
    xs.push_back(std::nextafter(edge, 2.0f * edge));
  }
  std::vector<gpu::SgProbeCase> em;
  for (double x : xs) em.push_back(probe(SG_PROBE_EM1X, {float(x), 0, 0, 0}));
  auto e = run(em);
  for (size_t i = 0; i < xs.size(); ++i)
    expectNear(e[i].x.x, gi::em1x(double(em[i].a.x)), kFew, 0.0,
               "em1x(" + std::to_string(xs[i]) + ")");
  for (size_t i = xs.size() - 4; i < xs.size(); i += 2)
    expectNear(e[i].x.x, e[i + 1].x.x, kFew, 0.0, "em1x jump at |x| = 1");

  const std::vector<double> lambdas = {0.0, 1e-8, 0.25, 0.5, 1.0, 8.0, 10.0, 1e3, kMaxSharpness};
  std::vector<gpu::SgProbeCase> cases;
  for (double l : lambdas) {
    cases.push_back(probe(SG_PROBE_INTEGRAL, {float(l), 0, 0, 0}));
    cases.push_back(probe(SG_PROBE_CLAMPED_COSINE, {float(l), 0.3f, 0, 0}));
  }
  for (float edge : {8.0f, 0.5f}) {  // S's exp skip, U and L's Taylor switch
    cases.push_back(probe(SG_PROBE_INTEGRAL, {edge, 0, 0, 0}));
    cases.push_back(probe(SG_PROBE_INTEGRAL, {std::nextafter(edge, 2.0f * edge), 0, 0, 0}));
    cases.push_back(probe(SG_PROBE_CLAMPED_COSINE, {edge, 0.3f, 0, 0}));
    cases.push_back(
        probe(SG_PROBE_CLAMPED_COSINE, {std::nextafter(edge, 2.0f * edge), 0.3f, 0, 0}));
  }
  auto r = run(cases);
  for (size_t i = 0; i < 2 * lambdas.size(); i += 2) {
    const double l = cases[i].a.x;
    const std::string at = std::string("(").append(std::to_string(l)).append(")");
    expectNear(r[i].x.x, gi::sgIntegral(l), kFew, 0.0, "S" + at);
    // U and L: the closed forms lose a few bits to cancellation just above the switch.
    expectNear(r[i + 1].x.y, gi::clampedCosineUpperIntegral(l), kChain, 0.0, "U" + at);
    // L underflows to 0 with e^-lambda; its absolute floor is FLT_MIN's neighbourhood.
    expectNear(r[i + 1].x.z, gi::clampedCosineLowerIntegral(l), kChain, 1e-30, "L" + at);
    EXPECT_GT(r[i].x.x, 0.0f) << "S" << at;
  }
  expectNear(r[2].x.x, 4.0 * kPi, kFew, 0.0, "S(1e-8) = 4 pi");
  expectNear(r[2 * lambdas.size() - 2].x.x, 2.0 * kPi / kMaxSharpness, kFew, 0.0, "S(2^41)");
  const size_t edges = 2 * lambdas.size();
  expectNear(r[edges].x.x, r[edges + 1].x.x, kFew, 0.0, "S jump at 8");
  expectNear(r[edges + 6].x.y, r[edges + 7].x.y, kFew, 0.0, "U jump at 0.5");
  expectNear(r[edges + 6].x.z, r[edges + 7].x.z, kFew, 0.0, "L jump at 0.5");
}

// Cases 11, 13 and 18 (diffuse): the normalised SG x clamped cosine D(lambda, c) against the
// oracle over lambda in [0, 2^41] and c in [-1, 1] (kChain: erfc chains); D(0, c) = 1 for every
// c (white furnace); behind the receiver (c < 0) D stays >= 0 and <= its mirror D(lambda, -c);
// grazing (c = 0) finite and positive.
TEST_F(StabilitySg, ClampedCosineGrazingBehindAndWhiteFurnace) {
  const std::vector<double> lambdas = {0.0, 1e-8, 0.1, 0.5, 1.0, 10.0, 100.0, 1e4, kMaxSharpness};
  const std::vector<double> cosines = {-1.0, -0.5, -0.01, 0.0, 0.01, 0.5, 1.0};
  std::vector<gpu::SgProbeCase> cases;
  for (double l : lambdas)
    for (double c : cosines)
      cases.push_back(probe(SG_PROBE_CLAMPED_COSINE, {float(l), float(c), 0, 0}));
  auto r = run(cases);
  size_t i = 0;
  for (double l : lambdas)
    for (double c : cosines) {
      const std::string at = "D(" + std::to_string(l) + ", " + std::to_string(c) + ")";
      const double ref = gi::sgClampedCosineIntegralOverPi(l, c);
      // Behind the receiver D falls like e^(-2 lambda): below 1e-30 only its sign matters.
      expectNear(r[i].x.x, ref, kChain, 1e-30, at);
      EXPECT_GE(r[i].x.x, 0.0f) << at;
      if (l == 0.0) {
        EXPECT_NEAR(r[i].x.x, 1.0f, kFew) << at << ": white furnace";
      }
      if (c < 0.0) {
        const size_t mirror = i + (cosines.size() - 1 - 2 * (i % cosines.size()));
        EXPECT_LE(r[i].x.x, r[mirror].x.x) << at << " exceeds its front-facing mirror";
      }
      if (c == 0.0) {
        EXPECT_GT(r[i].x.x, 0.0f) << at;
      }
      ++i;
    }
}

// Case 12 (and 3's v = 0): a receiver exactly at the lobe's mean, with variance 0 and 1e-6: the
// spot sharpness d^2 / v' is 0, so the radiance SG is the emitted lobe seen back along -xi with
// log amplitude logScale - log v', v' = max(v, FLT_MIN): finite, as the oracle.
TEST_F(StabilitySg, ReceiverAtTheVsglMean) {
  const glm::vec3 mean(0.7f, 1.3f, -2.1f);
  const glm::vec3 axis = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
  std::vector<gpu::SgProbeCase> cases;
  for (float variance : {0.0f, 1e-6f})
    for (float sharpness : {0.0f, 3.0f, float(kMaxSharpness)})
      cases.push_back(
          probe(SG_PROBE_VSGL_RADIANCE, {mean, variance}, {axis, sharpness}, {mean, -1.5f}));
  auto r = run(cases);
  for (size_t i = 0; i < cases.size(); ++i) {
    gpu::VsglLobe lobe{};
    lobe.meanVariance = cases[i].a;
    lobe.axisSharpness = cases[i].b;
    const gi::VsglIncomingRadiance ref = gi::vsglIncomingRadiance(lobe, glm::dvec3(mean));
    const std::string what =
        "v " + std::to_string(cases[i].a.w) + ", lambda " + std::to_string(cases[i].b.w);
    expectNear(r[i].x.w, cases[i].b.w, kFew, 0.0, what + ": lambda_p = lambda");
    EXPECT_NEAR(glm::dot(glm::vec3(r[i].x), -axis), 1.0f, 1e-6f) << what << ": axis = -xi";
    // The oracle keeps log E in its scale; the probe folds it, with logScale, into l_p.
    expectNear(r[i].y.x,
               -1.5 + ref.sg.logAmplitude - std::log(std::max(double(cases[i].a.w), 0x1p-126)),
               kFew, 1.0, what + ": l_p");
  }
}

// Cases 10, 15 and 18 (glossy): the GGX reflection of an SG light at grazing and below-horizon
// views (n . v = 1e-4, 0, -0.3: normal maps), normal incidence (no tangential view: any
// azimuth), roughness 0 (alpha floored at 1e-3) and 1 (lambda_r = 0, beta = FLT_MAX) and
// sharpness 0 to 2^41: finite, >= 0, and the oracle's value (kChain relative; an absolute floor
// of 1e-6 of the lobe's peak scale 1 / alpha^2 for the values that are 0 in exact arithmetic).
// A constant light (lambda = 0) returns the same model's albedo on both sides.
TEST_F(StabilitySg, GlossyAtGrazingViewAndRoughnessExtremes) {
  const glm::vec3 n(0, 0, 1);
  std::vector<glm::vec3> views;
  for (float nv : {1.0f, 0.5f, 1e-4f, 0.0f, -0.3f})
    views.push_back(glm::normalize(glm::vec3(std::sqrt(std::max(0.0f, 1.0f - nv * nv)), 0.0f, nv)));
  std::vector<gpu::SgProbeCase> cases;
  for (const glm::vec3& v : views)
    for (float alpha : {0.0f, 1e-3f, 0.3f, 1.0f})
      for (float lambda : {0.0f, 1.0f, 100.0f, float(kMaxSharpness)}) {
        const glm::vec3 mirror = glm::normalize(glm::vec3(-v.x, -v.y, std::abs(v.z) + 1e-3f));
        cases.push_back(probe(SG_PROBE_GGX_REFLECTION, {mirror, lambda}, {n, alpha}, {v, 0.04f}));
      }
  auto r = run(cases);
  for (size_t i = 0; i < cases.size(); ++i) {
    const gpu::SgProbeCase& c = cases[i];
    const glm::dvec3 ref =
        gi::sgGgxReflection({glm::dvec3(glm::vec3(c.a)), double(c.a.w), 0.0}, glm::dvec3(n),
                            glm::dvec3(glm::vec3(c.c)), double(c.b.w), glm::dvec3(c.c.w), 1.0);
    const double alpha = std::max(double(c.b.w), gi::kSgGgxMinAlpha);
    const std::string what = "n.v " + std::to_string(c.c.z) + ", alpha " + std::to_string(c.b.w) +
                             ", lambda " + std::to_string(c.a.w);
    EXPECT_GE(r[i].x.x, 0.0f) << what;
    expectNear(r[i].x.x, ref.x, kChain, 1e-6 / (alpha * alpha), what);
  }
}

// Cases 10 and 15 (the VPL side): a VPL's specular lobe lit from grazing (w_z -> 0+), from below
// the horizon (w_z < 0: the dominant-normal identity that does not cancel), from the normal (no
// tangential part) and at roughness 0 and 1: finite, a unit axis, a sharpness in [0, 2^41], the
// oracle's lobe: the axis within 1e-6 in cosine; the sharpness lambda_h h.n / (4 |w . h|)
// divides by |w . h|, which grazing light makes as small as alpha, and the unit vectors' own
// rounding (~u per component) reaches it as an absolute error of a few u: the relative bound is
// kChain + 8 u / |w . h|, with |w . h| = |w + axis| / 2 from the oracle's axis.
TEST_F(StabilitySg, VplSpecularLobeAtGrazingLightAndRoughnessExtremes) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.1f, 0.2f, 1.0f));
  std::vector<gpu::SgProbeCase> cases;
  for (float wz : {1.0f, 0.5f, 1e-4f, 0.0f, -1e-4f, -0.4f}) {
    glm::vec3 t = glm::normalize(glm::cross(n, glm::vec3(1, 0, 0)));
    const glm::vec3 toLight =
        glm::normalize(wz * n + std::sqrt(std::max(0.0f, 1.0f - wz * wz)) * t);
    for (float roughness : {0.0f, 0.03f, 0.5f, 1.0f})
      cases.push_back(probe(SG_PROBE_VPL_SPECULAR, {n, roughness}, {toLight, 0.0f}));
  }
  auto r = run(cases);
  for (size_t i = 0; i < cases.size(); ++i) {
    const gi::SgLobe ref =
        gi::specularLobe(glm::dvec3(n), glm::dvec3(glm::vec3(cases[i].b)), double(cases[i].a.w));
    const std::string what = "w.n " + std::to_string(glm::dot(glm::vec3(cases[i].b), n)) +
                             ", roughness " + std::to_string(cases[i].a.w);
    EXPECT_NEAR(glm::length(glm::vec3(r[i].x)), 1.0f, 1e-6f) << what;
    EXPECT_GE(glm::dot(glm::dvec3(glm::vec3(r[i].x)), ref.axis), 1.0 - 1e-6) << what;
    EXPECT_GE(r[i].x.w, 0.0f) << what;
    EXPECT_LE(r[i].x.w, float(kMaxSharpness)) << what;
    const double wh = glm::length(glm::dvec3(glm::vec3(cases[i].b)) + ref.axis) / 2.0;
    expectNear(r[i].x.w, ref.sharpness, kChain + 8.0 * std::ldexp(1.0, -24) / wh, 0.0,
               what + ": sharpness");
  }
}

// The culling bound (common/vsgl_bound.glsl) against its double twin (reference/vsgl_bound.h)
// on its hard inputs: zero variance, a group around the mean (the spot covers every
// direction), a point group (radius 0), isotropic and 2^41-sharp emission, mirror-like and
// grazing receivers, no glossy term. Tolerance 3e-3 relative plus 1e-30: the cone angles come
// from acos and asin, which lavapipe evaluates to about 5e-5 rad, and exp(lambda (cos - 1))
// turns an angle error d into lambda sin(theta) d of relative error (measured: 1.3e-3 for the
// case with lambda = 40 at 34 degrees, i.e. d = 6e-5). The bounds' 1e-3 rad margin, on both
// sides, keeps the fp32 bound conservative all the same. The cases whose emission is neither 1
// nor 0 keep lambda <= 40; a 2^41-sharp lobe facing away is 0 on both sides.
TEST_F(StabilitySg, VsglBoundMatchesItsTwin) {
  struct Case {
    glm::vec4 meanVariance, axisSharpness, centreRadius, normalCone, material, view;
  };
  const float pi = 3.14159265f;
  // clang-format off
  std::vector<Case> cases = {
      // mean, variance | axis, sharpness | centre, radius | normal axis, angle |
      // power, albedo, fresnel, alpha | n.v, specular albedo
      {{0, 1, 0, 1e-3f}, {0, -1, 0, 2.2925f}, {0, 0, 0, 0.05f}, {0, 1, 0, 0.2f}, {1, 0.8f, 1, 0.25f}, {0.7f, 0.1f, 0, 0}},
      {{0, 1, 0, 0.0f}, {0, -1, 0, 2.2925f}, {0, 0, 0, 0.05f}, {0, 1, 0, 0.2f}, {1, 0.8f, 1, 0.25f}, {0.7f, 0.1f, 0, 0}},
      {{0, 0.01f, 0, 1e-2f}, {1, 0, 0, 0.0f}, {0, 0, 0, 0.05f}, {0, 1, 0, 0.0f}, {2, 0.5f, 0.5f, 1e-3f}, {1e-4f, 0.5f, 0, 0}},
      {{0, 3, 1, 1e-4f}, {0, -0.6f, -0.8f, 40.0f}, {0, 0, 0, 0.0f}, {0, 1, 0, 0.0f}, {1, 1, 1, 0.1f}, {0.2f, 0.9f, 0, 0}},
      {{0, 3, 1, 1e-4f}, {0, 0.6f, 0.8f, 2.0e12f}, {0, 0, 0, 0.3f}, {0, 1, 0, 0.5f}, {1, 1, 1, 0.1f}, {0.2f, 0.9f, 0, 0}},
      {{5, -2, 0, 0.5f}, {-1, 0, 0, 5.0f}, {0, 0, 0, 0.2f}, {0, 1, 0, 1.0f}, {3, 0.3f, 0, 1.0f}, {1.0f, 0.0f, 0, 0}},
      {{0, 2, 0, 1e-6f}, {0, -1, 0, 2.2925f}, {0, 0, 0, 0.1f}, {0, 1, 0, pi}, {1, 1, 0.04f, 0.5f}, {0.5f, 0.05f, 0, 0}},
  };
  // clang-format on
  std::vector<gpu::SgProbeCase> probes;
  for (const Case& c : cases) {
    gpu::SgProbeCase p = probe(
        SG_PROBE_VSGL_BOUND, c.meanVariance,
        glm::vec4(glm::normalize(glm::vec3(c.axisSharpness)), c.axisSharpness.w), c.centreRadius);
    p.d = glm::vec4(glm::normalize(glm::vec3(c.normalCone)), c.normalCone.w);
    // The shader's per-lobe constant log(P / (2 pi S(lambda))), in double.
    const double logScale = std::log(double(c.material.x)) - std::log(2.0 * kPi) -
                            std::log(gi::sgIntegral(c.axisSharpness.w));
    p.e = glm::vec4(float(logScale), c.material.y, c.material.z, c.material.w);
    p.f = glm::vec4(c.view.x, c.view.y, 0.0f, 0.0f);
    probes.push_back(p);
  }
  const std::vector<gpu::SgProbeResult> results = run(probes);
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    gpu::VsglLobe lobe{};
    lobe.meanVariance = c.meanVariance;
    lobe.axisSharpness = probes[i].b;
    lobe.power = glm::vec4(glm::vec3(c.material.x), c.material.x);
    gi::VsglReceivers group;
    group.centre = glm::dvec3(c.centreRadius);
    group.radius = c.centreRadius.w;
    group.normalAxis = glm::dvec3(glm::vec3(probes[i].d));
    group.normalAngle = c.normalCone.w;
    group.albedo = c.material.y;
    group.fresnel = c.material.z;
    group.alpha = c.material.w;
    group.viewCosine = c.view.x;
    group.specularAlbedo = c.view.y;
    const gi::VsglLobeBound want = gi::vsglLobeBound(lobe, group);
    expectNear(results[i].x.x, want.diffuse, 3e-3, 1e-30, "case " + std::to_string(i) + " diffuse");
    expectNear(results[i].x.y, want.glossy, 3e-3, 1e-30, "case " + std::to_string(i) + " glossy");
  }
}

}  // namespace
