#include "gi/settings.h"

#include <bit>
#include <exception>

#include "passes/brsm_pdf.h"
#include "passes/ism.h"
#include "passes/kmeans.h"
#include "shared/adaptive_shading.h"

namespace gi {
namespace {

std::string field(const char* name, const std::string& value, const char* problem) {
  return std::string("Settings.") + name + ": " + value + " " + problem;
}

}  // namespace

std::string validateSettings(const Settings& s) {
  auto pow2In = [](uint32_t v, uint32_t lo, uint32_t hi) {
    return std::has_single_bit(v) && v >= lo && v <= hi;
  };
  const uint32_t maxCount = s.maxVsglCount ? s.maxVsglCount : s.vsglCount;
  if (!pow2In(s.rsmSize, 16, 2048))
    return field("rsmSize", std::to_string(s.rsmSize), "is not a power of two in [16, 2048]");
  if (maxCount < 1 || maxCount > kMaxVsglCount)
    return field("maxVsglCount", std::to_string(maxCount),
                 ("is outside [1, " + std::to_string(kMaxVsglCount) + "]").c_str());
  if (s.vsglCount < 1 || s.vsglCount > maxCount)
    return field("vsglCount", std::to_string(s.vsglCount),
                 ("is outside [1, maxVsglCount = " + std::to_string(maxCount) + "]").c_str());
  if (!(s.kernelScale >= 1.0f && s.kernelScale <= float(s.vsglCount)))
    return field("kernelScale", std::to_string(s.kernelScale),
                 ("is outside [1, vsglCount = " + std::to_string(s.vsglCount) + "]").c_str());
  if (!(s.surfaceTolerance >= 0.0f && s.surfaceTolerance <= 10.0f))
    return field("surfaceTolerance", std::to_string(s.surfaceTolerance), "is outside [0, 10]");
  if (s.rule != KernelRule::Tok15 && s.rule != KernelRule::Modified)
    return field("rule", std::to_string(uint32_t(s.rule)), "is neither Tok15 nor Modified");
  if (s.pdf != PdfKind::Flux && s.pdf != PdfKind::Brsm)
    return field("pdf", std::to_string(uint32_t(s.pdf)), "is neither Flux nor Brsm");
  if (s.method > VsglMethod::Vpl)
    return field("method", std::to_string(uint32_t(s.method)),
                 "is none of FilteredImportanceSampling, KmeansImage, KmeansWorld, Vpl");
  if (s.kmeans.iterations < 1 || s.kmeans.iterations > KmeansClustering::kMaxIterations)
    return field(
        "kmeans.iterations", std::to_string(s.kmeans.iterations),
        ("is outside [1, " + std::to_string(KmeansClustering::kMaxIterations) + "]").c_str());
  // The passes' own checks, which name the field, so the ranges are written once.
  try {
    validateBrsmSettings(s.brsm, s.rsmSize);
  } catch (const std::exception& e) {
    return std::string("Settings.brsm: ") + e.what();
  }
  try {
    validateIsmSettings(s.ism);
  } catch (const std::exception& e) {
    return std::string("Settings.ism: ") + e.what();
  }
  const AdaptiveSettings& a = s.adaptive;
  if (a.coarsestLevel > ADAPTIVE_MAX_LEVEL)
    return field("adaptive.coarsestLevel", std::to_string(a.coarsestLevel), "is outside [0, 3]");
  if (!(a.lightTolerance >= 0.0f && a.lightTolerance <= 10.0f))
    return field("adaptive.lightTolerance", std::to_string(a.lightTolerance), "is outside [0, 10]");
  if (!(a.planeTolerance >= 0.0f && a.planeTolerance <= 1.0f))
    return field("adaptive.planeTolerance", std::to_string(a.planeTolerance), "is outside [0, 1]");
  if (!(a.normalAngle >= 0.0f && a.normalAngle <= 3.14159265f))
    return field("adaptive.normalAngle", std::to_string(a.normalAngle), "is outside [0, pi]");
  if (!(a.roughnessTolerance >= 0.0f && a.roughnessTolerance <= 1.0f))
    return field("adaptive.roughnessTolerance", std::to_string(a.roughnessTolerance),
                 "is outside [0, 1]");
  if (!(a.f0Tolerance >= 0.0f && a.f0Tolerance <= 1.0f))
    return field("adaptive.f0Tolerance", std::to_string(a.f0Tolerance), "is outside [0, 1]");
  const EnvironmentSettings& e = s.environment;
  if (uint32_t(e.method) > uint32_t(EnvironmentMethod::SgLights))
    return field("environment.method", std::to_string(uint32_t(e.method)),
                 "is not Fis or SgLights");
  if (e.sgLightCount < 1 || e.sgLightCount > 4096)
    return field("environment.sgLightCount", std::to_string(e.sgLightCount),
                 "is outside [1, 4096]");
  if (!(e.sgKernelScale >= 1.0f && e.sgKernelScale <= float(e.sgLightCount)))
    return field("environment.sgKernelScale", std::to_string(e.sgKernelScale),
                 ("is outside [1, sgLightCount = " + std::to_string(e.sgLightCount) + "]").c_str());
  if (e.method == EnvironmentMethod::SgLights && e.brdf != EnvironmentBrdf::Ggx)
    return field("environment.brdf", std::to_string(uint32_t(e.brdf)),
                 "is not Ggx: SG lights shade the G-buffer's GGX only");
  if (e.sampleCount < 1 || e.sampleCount > 4096)
    return field("environment.sampleCount", std::to_string(e.sampleCount), "is outside [1, 4096]");
  if (uint32_t(e.sampling) > uint32_t(EnvironmentSampling::Randomised))
    return field("environment.sampling", std::to_string(uint32_t(e.sampling)),
                 "is not Filtered, Unfiltered or Randomised");
  if (uint32_t(e.brdf) > uint32_t(EnvironmentBrdf::Ward))
    return field("environment.brdf", std::to_string(uint32_t(e.brdf)), "is not Ggx, Phong or Ward");
  if (!(e.wardAnisotropy >= 0.01f && e.wardAnisotropy <= 100.0f))
    return field("environment.wardAnisotropy", std::to_string(e.wardAnisotropy),
                 "is outside [0.01, 100]");
  if (!(e.kernelScale >= 1.0f && e.kernelScale <= 16.0f))
    return field("environment.kernelScale", std::to_string(e.kernelScale), "is outside [1, 16]");
  if (e.mapSize < 16 || e.mapSize > 2048 || (e.mapSize & (e.mapSize - 1)) != 0)
    return field("environment.mapSize", std::to_string(e.mapSize),
                 "is not a power of two in [16, 2048]");
  if (!(s.culling.budget >= 0.0f && s.culling.budget <= 0.5f))
    return field("culling.budget", std::to_string(s.culling.budget), "is outside [0, 0.5]");
  if (s.debugVsgl < -1 || (s.debugVsgl >= 0 && uint32_t(s.debugVsgl) >= s.vsglCount))
    return field("debugVsgl", std::to_string(s.debugVsgl),
                 ("is neither -1 nor a VSGL index below vsglCount = " + std::to_string(s.vsglCount))
                     .c_str());
  return {};
}

}  // namespace gi
