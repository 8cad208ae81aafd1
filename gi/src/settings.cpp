#include "gi/settings.h"

#include <bit>
#include <exception>

#include "passes/ism.h"

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
  if (maxCount < 1 || maxCount > 65535)
    return field("maxVsglCount", std::to_string(maxCount), "is outside [1, 65535]");
  if (s.vsglCount < 1 || s.vsglCount > maxCount)
    return field("vsglCount", std::to_string(s.vsglCount),
                 ("is outside [1, maxVsglCount = " + std::to_string(maxCount) + "]").c_str());
  if (!(s.kernelScale >= 1.0f && s.kernelScale <= float(s.vsglCount)))
    return field("kernelScale", std::to_string(s.kernelScale),
                 ("is outside [1, vsglCount = " + std::to_string(s.vsglCount) + "]").c_str());
  if (s.rule != KernelRule::Tok15 && s.rule != KernelRule::Modified)
    return field("rule", std::to_string(uint32_t(s.rule)), "is neither Tok15 nor Modified");
  if (s.pdf != PdfKind::Flux && s.pdf != PdfKind::Brsm)
    return field("pdf", std::to_string(uint32_t(s.pdf)), "is neither Flux nor Brsm");
  if (s.brsm.importanceCount < 1 || s.brsm.importanceCount > 65536)
    return field("brsm.importanceCount", std::to_string(s.brsm.importanceCount),
                 "is outside [1, 65536]");
  if (!std::has_single_bit(s.brsm.gridSize) || s.brsm.gridSize > s.rsmSize)
    return field(
        "brsm.gridSize", std::to_string(s.brsm.gridSize),
        ("is not a power of two in [1, rsmSize = " + std::to_string(s.rsmSize) + "]").c_str());
  if (!(s.brsm.fluxMix > 0.0f && s.brsm.fluxMix <= 1.0f))
    return field("brsm.fluxMix", std::to_string(s.brsm.fluxMix), "is outside (0, 1]");
  try {
    validateIsmSettings(s.ism);
  } catch (const std::exception& e) {
    return std::string("Settings.ism: ") + e.what();
  }
  if (s.debugVsgl < -1 || (s.debugVsgl >= 0 && uint32_t(s.debugVsgl) >= s.vsglCount))
    return field("debugVsgl", std::to_string(s.debugVsgl),
                 ("is neither -1 nor a VSGL index below vsglCount = " + std::to_string(s.vsglCount))
                     .c_str());
  return {};
}

}  // namespace gi
