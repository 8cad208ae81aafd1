#include "settings_fields.h"

#include <bit>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <system_error>
#include <type_traits>

#include "engine/error.h"

namespace samples {
namespace {

using Kind = SettingField::Kind;

// A field's value as a double and back: every field is a bool, an enum over uint32_t, a
// uint32_t, an int32_t or a float, all exact in a double.
template <class T>
double asDouble(T value) {
  if constexpr (std::is_enum_v<T>)
    return static_cast<double>(static_cast<std::underlying_type_t<T>>(value));
  else
    return static_cast<double>(value);
}
template <class T>
T fromDouble(double value) {
  if constexpr (std::is_enum_v<T>)
    return static_cast<T>(static_cast<std::underlying_type_t<T>>(value));
  else if constexpr (std::is_same_v<T, bool>)
    return value != 0.0;
  else
    return static_cast<T>(value);
}

// The get/set pair of the member at `path` of gi::Settings, as captureless lambdas.
struct Access {
  double (*get)(const gi::Settings&);
  void (*set)(gi::Settings&, double);
};
#define SETTING_ACCESS(path)                                      \
  (Access{[](const gi::Settings& s) { return asDouble(s.path); }, \
          [](gi::Settings& s, double v) { s.path = fromDouble<decltype(s.path)>(v); }})

// brsm.fluxMix's range is (0, 1]: the smallest positive float stands for the open end, so the
// table accepts exactly what validateSettings does (fluxMix > 0).
constexpr double kAboveZero = std::numeric_limits<float>::denorm_min();

enum Flags : unsigned { kPlain = 0, kPowerOfTwo = 1, kCreation = 2 };

SettingField number(Kind kind, const char* group, const char* key, const char* unit, double min,
                    double max, unsigned flags, Access access, const char* help) {
  SettingField f{group, key, unit, help, kind, min, max};
  f.powerOfTwo = (flags & kPowerOfTwo) != 0;
  f.creation = (flags & kCreation) != 0;
  f.get = access.get;
  f.set = access.set;
  return f;
}
SettingField onOff(const char* group, const char* key, Access access, const char* help) {
  return number(Kind::Bool, group, key, "", 0, 1, kPlain, access, help);
}
SettingField choice(const char* group, const char* key, unsigned flags,
                    std::vector<std::pair<const char*, uint32_t>> words, Access access,
                    const char* help) {
  const double max = static_cast<double>(words.size()) - 1;
  SettingField f = number(Kind::Choice, group, key, "", 0, max, flags, access, help);
  f.choices = std::move(words);
  return f;
}

const char* const kVsgls = "VSGLs";
const char* const kKmeans = "k-means";
const char* const kBrsm = "BRSM";
const char* const kIsm = "ISM";
const char* const kPlanner = "Planner";
const char* const kAdaptive = "Adaptive shading";
const char* const kCulling = "Culling";
const char* const kEnvironment = "Environment";
const char* const kDebug = "Debug";

// Ranges are settings.h's for each field alone. Float bounds are written as float literals:
// validateSettings compares the float field with float constants (0.01f is a little below 0.01),
// and so must the table.
std::vector<SettingField> makeTable() {
  constexpr double kMaxVsgls = gi::kMaxVsglCount;
  constexpr Kind kUint = Kind::Uint;
  constexpr Kind kFloat = Kind::Float;
  return {
      // VSGLs
      number(kUint, kVsgls, "rsmSize", "texels", 16, 2048, kPowerOfTwo | kCreation,
             SETTING_ACCESS(rsmSize),
             "RSM side; cost ~ rsmSize^2 in the RSM, attribute and mip passes (x6 for a point "
             "light)"),
      number(kUint, kVsgls, "maxVsglCount", "VSGLs", 0, kMaxVsgls, kCreation,
             SETTING_ACCESS(maxVsglCount),
             "largest VSGL count this instance is asked for, 0 = vsglCount; sizes the VSGL buffer "
             "and the ISM atlas"),
      number(kUint, kVsgls, "vsglCount", "VSGLs", 1, kMaxVsgls, kPlain, SETTING_ACCESS(vsglCount),
             "VSGLs per frame N (at most maxVsglCount); shading costs ~ N x pixels"),
      // settings.h: [1, vsglCount], and vsglCount is at most kMaxVsglCount.
      number(kFloat, kVsgls, "kernelScale", "", 1.0f, kMaxVsgls, kPlain,
             SETTING_ACCESS(kernelScale),
             "K: each kernel holds K/N of the PDF mass (K <= vsglCount); larger = blurrier, "
             "steadier"),
      choice(kVsgls, "rule", kPlain,
             {{"modified", uint32_t(gi::KernelRule::Modified)},
              {"tok15", uint32_t(gi::KernelRule::Tok15)}},
             SETTING_ACCESS(rule),
             "kernel size: K/N of the PDF mass (modified FIS) or the PDF at its centre (Tok15)"),
      choice(kVsgls, "pdf", kPlain,
             {{"flux", uint32_t(gi::PdfKind::Flux)}, {"brsm", uint32_t(gi::PdfKind::Brsm)}},
             SETTING_ACCESS(pdf),
             "PDF over the RSM: reflected flux (view-independent) or the view-dependent BRSM"),
      choice(kVsgls, "method", kPlain,
             {{"fis", uint32_t(gi::VsglMethod::FilteredImportanceSampling)},
              {"kmeans-2d", uint32_t(gi::VsglMethod::KmeansImage)},
              {"kmeans-3d", uint32_t(gi::VsglMethod::KmeansWorld)},
              {"vpl", uint32_t(gi::VsglMethod::Vpl)}},
             SETTING_ACCESS(method),
             "filtered importance sampling, or a baseline: k-means in image or world space, VPLs"),
      onOff(kVsgls, "glossy", SETTING_ACCESS(glossy),
            "shade the glossy (GGX) term; off, shading costs about 40 % less"),
      onOff(kVsgls, "planarEmitters", SETTING_ACCESS(planarEmitters),
            "flat VSGLs emit nothing below or along their plane; off = plain SG emitters"),
      onOff(kVsgls, "broadReflections", SETTING_ACCESS(broadReflections),
            "reflections as broad as the Lambert lobe join the diffuse lobe; off = every "
            "reflection glossy (steadier, less accurate on mirror-and-matte mixtures)"),
      number(kFloat, kVsgls, "surfaceTolerance", "", 0.0f, 10.0f, kPlain,
             SETTING_ACCESS(surfaceTolerance),
             "kernels whose mean leaves their surface by more than this many standard "
             "deviations shrink onto it; 0 = off, smaller = more accurate, more flicker"),
      // k-means
      number(kUint, kKmeans, "kmeans.iterations", "", 1, 64, kPlain,
             SETTING_ACCESS(kmeans.iterations),
             "Lloyd iterations per frame; each ~ rsmSize^2 x N distance tests plus a sort"),
      onOff(kKmeans, "kmeans.pdfWeighted", SETTING_ACCESS(kmeans.pdfWeighted),
            "centres weighted by the PDF; off = every lit texel weighs the same"),
      onOff(kKmeans, "kmeans.temporal", SETTING_ACCESS(kmeans.temporal),
            "start from the previous frame's centres; off = fresh seeds every frame"),
      // BRSM
      number(kUint, kBrsm, "brsm.importanceCount", "VSGLs", 1, gi::kMaxImportanceCount, kCreation,
             SETTING_ACCESS(brsm.importanceCount),
             "importance VSGLs from the camera G-buffer; stage B is linear in it"),
      // settings.h: [1, rsmSize], and rsmSize is at most 2048.
      number(kUint, kBrsm, "brsm.gridSize", "cells", 1, 2048, kPowerOfTwo | kCreation,
             SETTING_ACCESS(brsm.gridSize),
             "stage-B cells per side (at most rsmSize); cost ~ gridSize^2 x importanceCount"),
      number(kFloat, kBrsm, "brsm.fluxMix", "", kAboveZero, 1.0f, kPlain,
             SETTING_ACCESS(brsm.fluxMix),
             "share of the flux PDF mixed in, so no lit texel has p = 0; 1 = the flux PDF"),
      // ISM: every ism.* field is a creation field (IndirectLighting::setSettings), ismEnabled not.
      onOff(kIsm, "ismEnabled", SETTING_ACCESS(ismEnabled),
            "imperfect-shadow-map visibility; off, light leaks through walls (~20 % less shading)"),
      number(kUint, kIsm, "ism.mapSize", "texels", 16, 256, kPowerOfTwo | kCreation,
             SETTING_ACCESS(ism.mapSize),
             "paraboloid map side per VSGL; atlas maxVsglCount x mapSize^2 x 4 bytes"),
      number(kUint, kIsm, "ism.pointCount", "points", 1 << 10, 1 << 22, kPowerOfTwo | kCreation,
             SETTING_ACCESS(ism.pointCount),
             "surface points in the pool, 24 bytes each, generated once per scene"),
      // settings.h: [64, pointCount], and pointCount is at most 2^22.
      number(kUint, kIsm, "ism.pointsPerVsgl", "points", 64, 1 << 22, kPowerOfTwo | kCreation,
             SETTING_ACCESS(ism.pointsPerVsgl),
             "points splatted per VSGL (at most pointCount); fewer = softer, leakier shadows"),
      number(kFloat, kIsm, "ism.depthBias", "m", 0.0f, 10.0f, kCreation,
             SETTING_ACCESS(ism.depthBias),
             "constant bias subtracted from the receiver's distance"),
      number(kFloat, kIsm, "ism.slopeBias", "texels", 0.0f, 16.0f, kCreation,
             SETTING_ACCESS(ism.slopeBias),
             "bias on tilted receivers, in texel footprints; larger = less acne, more leaking"),
      number(kFloat, kIsm, "ism.centreOffset", "m", 0.0f, 10.0f, kCreation,
             SETTING_ACCESS(ism.centreOffset),
             "ISM centre above the VSGL along its axis; larger loses contact shadows near it"),
      choice(kIsm, "ism.pcf", kCreation,
             {{"nearest", gi::IsmNearest}, {"bilinear", gi::IsmBilinear}, {"box3", gi::IsmBox3}},
             SETTING_ACCESS(ism.pcf),
             "depth-test filter: 1, 2 x 2 or 3 x 3 atlas reads per pixel-VSGL pair"),
      // Planner
      onOff(kPlanner, "planner.skipWithoutBounce", SETTING_ACCESS(planner.skipWithoutBounce),
            "skip every pass when no light can bounce"),
      onOff(kPlanner, "planner.skipSky", SETTING_ACCESS(planner.skipSky),
            "subgroups of pixels that all see the sky skip the VSGL loop"),
      onOff(kPlanner, "planner.skipWithoutOccluders", SETTING_ACCESS(planner.skipWithoutOccluders),
            "no ISMs when nothing can occlude (this also removes the ISMs' own errors)"),
      onOff(kPlanner, "planner.skipGlossyWithoutSpecular",
            SETTING_ACCESS(planner.skipGlossyWithoutSpecular),
            "no glossy term on texels with F0 = F90 = 0"),
      onOff(kPlanner, "reuse", SETTING_ACCESS(reuse),
            "rerun a pass only when its inputs changed since it last ran (bit-identical)"),
      // Adaptive shading
      onOff(kAdaptive, "adaptive.enabled", SETTING_ACCESS(adaptive.enabled),
            "shade coarse to fine, interpolating where surface, material and light agree"),
      number(kUint, kAdaptive, "adaptive.coarsestLevel", "", 0, 3, kPlain,
             SETTING_ACCESS(adaptive.coarsestLevel),
             "coarsest level L: one shaded pixel in 2^L x 2^L"),
      number(kFloat, kAdaptive, "adaptive.lightTolerance", "", 0.0f, 10.0f, kPlain,
             SETTING_ACCESS(adaptive.lightTolerance),
             "largest spread of the parents' light, as a fraction of its mean, to interpolate"),
      number(kFloat, kAdaptive, "adaptive.planeTolerance", "", 0.0f, 1.0f, kPlain,
             SETTING_ACCESS(adaptive.planeTolerance),
             "largest distance from a parent's tangent plane, as a fraction of the eye distance"),
      // pi as validateSettings writes it, a float.
      number(kFloat, kAdaptive, "adaptive.normalAngle", "rad", 0.0f, 3.14159265f, kPlain,
             SETTING_ACCESS(adaptive.normalAngle),
             "largest angle between the normals of a texel and its parents"),
      number(kFloat, kAdaptive, "adaptive.roughnessTolerance", "", 0.0f, 1.0f, kPlain,
             SETTING_ACCESS(adaptive.roughnessTolerance),
             "largest difference of perceptual roughness between a texel and its parents"),
      number(kFloat, kAdaptive, "adaptive.f0Tolerance", "", 0.0f, 1.0f, kPlain,
             SETTING_ACCESS(adaptive.f0Tolerance),
             "largest difference of any F0 channel or F90 between a texel and its parents"),
      // Culling
      onOff(kCulling, "culling.enabled", SETTING_ACCESS(culling.enabled),
            "skip VSGLs per subgroup of pixels while their bounds stay within the budget"),
      number(kFloat, kCulling, "culling.budget", "", 0.0f, 0.5f, kPlain,
             SETTING_ACCESS(culling.budget),
             "tau, the share of its light a pixel may lose; larger = more VSGLs skipped"),
      // Environment
      choice(kEnvironment, "environment.method", kPlain,
             {{"fis", uint32_t(gi::EnvironmentMethod::Fis)},
              {"sg", uint32_t(gi::EnvironmentMethod::SgLights)}},
             SETTING_ACCESS(environment.method),
             "filtered importance sampling per pixel, or SG lights sampled from the environment"),
      number(kUint, kEnvironment, "environment.sgLightCount", "lights", 1, 4096, kPlain,
             SETTING_ACCESS(environment.sgLightCount),
             "SG lights N, made once per environment; shading costs ~ N x pixels"),
      // settings.h: [1, sgLightCount], and sgLightCount is at most 4096.
      number(kFloat, kEnvironment, "environment.sgKernelScale", "", 1.0f, 4096.0f, kPlain,
             SETTING_ACCESS(environment.sgKernelScale),
             "K of the SG lights: each kernel holds K/N of the luminance (K <= sgLightCount)"),
      number(kUint, kEnvironment, "environment.sampleCount", "samples", 1, 4096, kPlain,
             SETTING_ACCESS(environment.sampleCount),
             "FIS samples per pixel; cost ~ samples x pixels"),
      choice(kEnvironment, "environment.sampling", kPlain,
             {{"filtered", uint32_t(gi::EnvironmentSampling::Filtered)},
              {"unfiltered", uint32_t(gi::EnvironmentSampling::Unfiltered)},
              {"randomised", uint32_t(gi::EnvironmentSampling::Randomised)}},
             SETTING_ACCESS(environment.sampling),
             "FIS reads the mip level a sample covers, level 0 (aliasing) or level 0 rotated per "
             "pixel (noise)"),
      choice(kEnvironment, "environment.brdf", kPlain,
             {{"ggx", uint32_t(gi::EnvironmentBrdf::Ggx)},
              {"phong", uint32_t(gi::EnvironmentBrdf::Phong)},
              {"ward", uint32_t(gi::EnvironmentBrdf::Ward)}},
             SETTING_ACCESS(environment.brdf),
             "the glossy lobe sampled and shaded; SG lights shade ggx only"),
      number(kFloat, kEnvironment, "environment.wardAnisotropy", "", 0.01f, 100.0f, kPlain,
             SETTING_ACCESS(environment.wardAnisotropy), "alpha_y / alpha_x of the Ward lobe"),
      number(kFloat, kEnvironment, "environment.kernelScale", "", 1.0f, 16.0f, kPlain,
             SETTING_ACCESS(environment.kernelScale),
             "K of FIS's mip-level rule; larger = blurrier, less aliasing"),
      number(kUint, kEnvironment, "environment.mapSize", "texels", 16, 2048,
             kPowerOfTwo | kCreation, SETTING_ACCESS(environment.mapSize),
             "paraboloid map side; 32 x mapSize^2 bytes with mips, made once per environment"),
      // Debug
      number(Kind::Int, kDebug, "debugVsgl", "", -1, kMaxVsgls - 1, kPlain,
             SETTING_ACCESS(debugVsgl),
             "VSGL (below vsglCount) whose ISM visibility is written out, -1 = none; one pass"),
  };
}

#undef SETTING_ACCESS

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return std::string(text.substr(first, last - first + 1));
}

// A number as files hold it: integers as integers, floats as the shortest text that reads back
// as the same float.
std::string numberText(const SettingField& f, double value) {
  char buffer[64];
  const auto [end, ec] =
      f.kind == Kind::Float
          ? std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(value))
          : std::to_chars(buffer, buffer + sizeof buffer, static_cast<int64_t>(value));
  return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

std::string rangeText(const SettingField& f) {
  std::string text = f.min == kAboveZero ? std::string("(0") : "[";
  if (f.min != kAboveZero) text += numberText(f, f.min);
  text += ", ";
  text += numberText(f, f.max);
  return text + "]";
}

std::string valueText(const SettingField& f, double value) {
  if (f.kind == Kind::Bool) return value != 0.0 ? "on" : "off";
  if (f.kind == Kind::Choice)
    for (const auto& [word, v] : f.choices)
      if (v == value) return word;
  return numberText(f, value);  // also a choice's value outside the enum, to show it
}

// The words of a Bool or Choice field.
std::vector<std::pair<const char*, uint32_t>> wordsOf(const SettingField& f) {
  if (f.kind == Kind::Bool) return {{"on", 1}, {"off", 0}};
  return f.choices;
}

// Reads `text` as field `f`'s value into `value`; false with the problem when it is not one.
bool readValue(const SettingField& f, const std::string& text, double& value,
               std::string& problem) {
  if (f.kind == Kind::Bool || f.kind == Kind::Choice) {
    std::string accepted;
    for (const auto& [word, v] : wordsOf(f)) {
      if (text == word) {
        value = v;
        return true;
      }
      accepted += (accepted.empty() ? "" : ", ") + std::string(word);
    }
    problem = "'" + text + "' is not one of " + accepted;
    return false;
  }
  const char* begin = text.data();
  const char* end = begin + text.size();
  std::from_chars_result result{};
  if (f.kind == Kind::Float) {
    // Read as a float, not a double then rounded: the shortest text of a float reads back
    // exactly only as a float.
    float v = 0.0f;
    result = std::from_chars(begin, end, v);
    value = v;
  } else {
    int64_t v = 0;
    result = std::from_chars(begin, end, v);
    value = static_cast<double>(v);
  }
  if (result.ptr != end ||
      (result.ec != std::errc() && result.ec != std::errc::result_out_of_range)) {
    problem = "'" + text + "' is not " + (f.kind == Kind::Float ? "a number" : "an integer");
    return false;
  }
  // Out of the type's range, NaN or beyond the field's range.
  if (result.ec == std::errc::result_out_of_range || !(value >= f.min && value <= f.max)) {
    problem = text + " is outside " + rangeText(f);
    return false;
  }
  if (f.powerOfTwo && !std::has_single_bit(static_cast<uint64_t>(value))) {
    problem = text + " is not a power of two";
    return false;
  }
  return true;
}

[[noreturn]] void fail(const std::string& source, int line, const std::string& key,
                       const std::string& problem) {
  throw engine::Error(source + ":" + std::to_string(line) + ": " + key + ": " + problem);
}

}  // namespace

const std::vector<SettingField>& settingFields() {
  static const std::vector<SettingField> table = makeTable();
  return table;
}

const SettingField* findSettingField(std::string_view key) {
  for (const SettingField& f : settingFields())
    if (key == f.key) return &f;
  return nullptr;
}

std::string formatSettings(const gi::Settings& s) {
  std::string text = "# gi::Settings (samples/common/settings_fields.h)\n";
  for (const SettingField& f : settingFields())
    text += std::string(f.key) + " = " + valueText(f, f.get(s)) + "\n";
  return text;
}

gi::Settings parseSettings(std::string_view text, const std::string& source,
                           const gi::Settings& base) {
  gi::Settings s = base;
  std::map<std::string, int, std::less<>> seen;  // key -> the line that set it
  int lineNumber = 0;
  for (size_t start = 0; start <= text.size();) {
    size_t newline = text.find('\n', start);
    if (newline == std::string_view::npos) newline = text.size();
    std::string_view line = text.substr(start, newline - start);
    start = newline + 1;
    ++lineNumber;
    line = line.substr(0, line.find('#'));
    if (trim(line).empty()) continue;
    const size_t equals = line.find('=');
    if (equals == std::string_view::npos)
      fail(source, lineNumber, trim(line), "expected 'key = value'");
    const std::string key = trim(line.substr(0, equals));
    const std::string valueWords = trim(line.substr(equals + 1));
    if (key.empty()) fail(source, lineNumber, "''", "expected 'key = value'");
    const SettingField* field = findSettingField(key);
    if (!field) fail(source, lineNumber, key, "unknown key");
    if (auto [it, added] = seen.emplace(key, lineNumber); !added)
      fail(source, lineNumber, key,
           "duplicate key (first on line " + std::to_string(it->second) + ")");
    if (valueWords.empty()) fail(source, lineNumber, key, "missing value");
    double value = 0.0;
    std::string problem;
    if (!readValue(*field, valueWords, value, problem)) fail(source, lineNumber, key, problem);
    field->set(s, value);
  }
  if (std::string bad = gi::validateSettings(s); !bad.empty())
    throw engine::Error(source + ": " + bad);
  return s;
}

gi::Settings readSettingsFile(const std::string& path, const gi::Settings& base) {
  std::error_code ec;
  std::ifstream file(path, std::ios::binary);
  // A directory opens as a file on Linux and reads as empty: it is no settings file.
  if (!file || std::filesystem::is_directory(path, ec)) throw engine::Error(path + ": cannot read");
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (file.bad()) throw engine::Error(path + ": cannot read");
  return parseSettings(text, path, base);
}

}  // namespace samples
