// The table of gi::Settings fields and its text files (samples/common/settings_fields.h): the
// table covers every member of every settings struct, each field's value survives a file
// exactly, and each kind of bad line is refused with one line naming the place and the problem.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/error.h"
#include "settings_fields.h"

namespace {

using samples::SettingField;
using Kind = SettingField::Kind;

// The number of members of an aggregate: the most initializers T{...} accepts, each of which
// converts to any member type (so a nested struct takes one, without brace elision).
struct AnyMember {
  template <class T>
  operator T() const;  // never defined: only used in unevaluated requires-expressions
};
template <class T, class... Members>
constexpr size_t memberCount() {
  if constexpr (requires { T{Members{}..., AnyMember{}}; })
    return memberCount<T, Members..., AnyMember>();
  else
    return sizeof...(Members);
}

// Keys of the table that start with `prefix` (with no dot after it).
size_t keysUnder(const std::string& prefix) {
  size_t n = 0;
  for (const SettingField& f : samples::settingFields()) {
    const std::string key = f.key;
    if (key.rfind(prefix, 0) == 0 && key.find('.', prefix.size()) == std::string::npos) ++n;
  }
  return n;
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A value of `f` other than its value in `s` that keeps `s` valid, or NaN when there is none.
double otherValue(const SettingField& f, const gi::Settings& s) {
  const double current = f.get(s);
  std::vector<double> candidates;
  if (f.kind == Kind::Bool) candidates = {current != 0.0 ? 0.0 : 1.0};
  if (f.kind == Kind::Choice)
    for (const auto& choice : f.choices) candidates.push_back(choice.second);
  if (f.kind == Kind::Uint || f.kind == Kind::Int)
    candidates = f.powerOfTwo ? std::vector<double>{current * 2, current / 2}
                              : std::vector<double>{current + 1, current - 1};
  if (f.kind == Kind::Float)  // values with no short exact decimal, e.g. 0.15f
    candidates = {double(float(current * 1.5)), double(float(current * 0.5)),
                  double(float((f.min + f.max) / 3))};
  candidates.push_back(f.min);
  candidates.push_back(f.max);
  for (double v : candidates) {
    if (v == current || !(v >= f.min && v <= f.max)) continue;
    if (f.powerOfTwo && !std::has_single_bit(static_cast<uint64_t>(v))) continue;
    gi::Settings changed = s;
    f.set(changed, v);
    if (f.get(changed) == v && gi::validateSettings(changed).empty()) return v;
  }
  return std::nan("");
}

std::string parseError(const std::string& text, const gi::Settings& base = {}) {
  try {
    samples::parseSettings(text, "test.txt", base);
  } catch (const engine::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SettingsFields, TableCoversEveryMemberOfEverySettingsStruct) {
  // A member added to settings.h changes these counts: give it a row in settingFields().
  EXPECT_EQ(memberCount<gi::KmeansSettings>(), keysUnder("kmeans."));
  EXPECT_EQ(memberCount<gi::BrsmSettings>(), keysUnder("brsm."));
  EXPECT_EQ(memberCount<gi::IsmSettings>(), keysUnder("ism."));
  EXPECT_EQ(memberCount<gi::PlannerSettings>(), keysUnder("planner."));
  EXPECT_EQ(memberCount<gi::AdaptiveSettings>(), keysUnder("adaptive."));
  EXPECT_EQ(memberCount<gi::CullingSettings>(), keysUnder("culling."));
  EXPECT_EQ(memberCount<gi::EnvironmentSettings>(), keysUnder("environment."));
  // Settings' own members, less its 7 nested structs.
  EXPECT_EQ(memberCount<gi::Settings>() - 7, keysUnder(""));
  // The same by hand, should the counting above ever break.
  EXPECT_EQ(samples::settingFields().size(), 49u);

  // Keys are unique and each names the field findSettingField returns.
  std::set<std::string> keys;
  for (const SettingField& f : samples::settingFields()) {
    EXPECT_TRUE(keys.insert(f.key).second) << f.key;
    EXPECT_EQ(samples::findSettingField(f.key), &f);
  }
  EXPECT_EQ(samples::findSettingField("nope"), nullptr);
}

TEST(SettingsFields, EachFieldChangesExactlyItsOwnLine) {
  // Together with the counts above: no two rows reach the same member, so every member has one.
  const gi::Settings defaults;
  const std::vector<std::string> before = linesOf(samples::formatSettings(defaults));
  ASSERT_EQ(before.size(), samples::settingFields().size() + 1);
  EXPECT_EQ(before[0], "# gi::Settings (samples/common/settings_fields.h)");
  for (size_t i = 0; i < samples::settingFields().size(); ++i) {
    const SettingField& f = samples::settingFields()[i];
    const double v = otherValue(f, defaults);
    ASSERT_FALSE(std::isnan(v)) << f.key << ": no other valid value";
    gi::Settings changed = defaults;
    f.set(changed, v);
    const std::vector<std::string> after = linesOf(samples::formatSettings(changed));
    ASSERT_EQ(after.size(), before.size());
    for (size_t line = 0; line < before.size(); ++line)
      EXPECT_EQ(after[line] != before[line], line == i + 1) << f.key << " changed: " << after[line];
  }
}

TEST(SettingsFields, EveryFieldRoundTripsThroughAFile) {
  const gi::Settings defaults;
  for (const SettingField& f : samples::settingFields()) {
    const double v = otherValue(f, defaults);
    ASSERT_FALSE(std::isnan(v)) << f.key;
    gi::Settings changed = defaults;
    f.set(changed, v);
    const std::string text = samples::formatSettings(changed);
    const gi::Settings read = samples::parseSettings(text, "round trip");
    EXPECT_EQ(f.get(read), v) << f.key << "\n" << text;
    EXPECT_EQ(samples::formatSettings(read), text) << f.key;
  }
}

TEST(SettingsFields, DefaultsRoundTripAndASubsetKeepsTheBase) {
  const gi::Settings defaults;
  const std::string text = samples::formatSettings(defaults);
  EXPECT_EQ(samples::formatSettings(samples::parseSettings(text, "defaults")), text);
  EXPECT_NE(text.find("\nrule = modified\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nbrsm.fluxMix = 0.1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nplanner.skipSky = on\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\ndebugVsgl = -1\n"), std::string::npos) << text;

  // Empty text, comments, blank lines, spaces and CRLF; the other fields stay the base's.
  gi::Settings base;
  base.vsglCount = 128;
  base.culling.enabled = true;
  EXPECT_EQ(samples::formatSettings(samples::parseSettings("", "empty", base)),
            samples::formatSettings(base));
  const gi::Settings s = samples::parseSettings(
      "# a comment\n\n  vsglCount=64   # trailing comment\r\n\tmethod = kmeans-3d\n"
      "environment.sampling = randomised\nism.pcf = box3\nadaptive.normalAngle = 0.5\n"
      "glossy = off",
      "subset", base);
  EXPECT_EQ(s.vsglCount, 64u);
  EXPECT_EQ(s.method, gi::VsglMethod::KmeansWorld);
  EXPECT_EQ(s.environment.sampling, gi::EnvironmentSampling::Randomised);
  EXPECT_EQ(s.ism.pcf, uint32_t(gi::IsmBox3));
  EXPECT_EQ(s.adaptive.normalAngle, 0.5f);
  EXPECT_FALSE(s.glossy);
  EXPECT_TRUE(s.culling.enabled);  // from the base
  EXPECT_EQ(s.rsmSize, base.rsmSize);
}

TEST(SettingsFields, RangesAgreeWithValidateSettings) {
  // Each field's own bounds are valid values (where the other fields allow them), and the
  // float bounds are the exact floats validateSettings compares with (0.01f, pi as a float).
  EXPECT_EQ(
      samples::parseSettings("environment.wardAnisotropy = 0.01", "t").environment.wardAnisotropy,
      0.01f);
  EXPECT_EQ(samples::parseSettings("adaptive.normalAngle = 3.1415927", "t").adaptive.normalAngle,
            3.14159265f);
  EXPECT_EQ(samples::parseSettings("brsm.fluxMix = 1e-30", "t").brsm.fluxMix, 1e-30f);
  EXPECT_EQ(samples::parseSettings("debugVsgl = 1023", "t").debugVsgl, 1023);
  EXPECT_EQ(samples::parseSettings("maxVsglCount = 32768\nvsglCount = 32768", "t").vsglCount,
            32768u);
  for (const SettingField& f : samples::settingFields()) {
    EXPECT_LE(f.min, f.max) << f.key;
    if (f.kind == Kind::Choice) {
      EXPECT_EQ(f.min, 0.0) << f.key;
      EXPECT_EQ(f.max + 1, double(f.choices.size())) << f.key;
    }
    if (f.kind == Kind::Bool) {
      EXPECT_EQ(f.min, 0.0) << f.key;
      EXPECT_EQ(f.max, 1.0) << f.key;
    }
    EXPECT_NE(std::string(f.group), "") << f.key;
    EXPECT_NE(std::string(f.help), "") << f.key;
  }
  for (const char* key : {"rsmSize", "maxVsglCount", "brsm.importanceCount", "brsm.gridSize",
                          "ism.mapSize", "ism.pointCount", "ism.pointsPerVsgl", "ism.depthBias",
                          "ism.slopeBias", "ism.centreOffset", "ism.pcf", "environment.mapSize"})
    EXPECT_TRUE(samples::findSettingField(key)->creation) << key;
  size_t creation = 0;
  for (const SettingField& f : samples::settingFields()) creation += f.creation;
  EXPECT_EQ(creation, 12u);
}

TEST(SettingsFields, EachBadLineIsOneLineNamingPlaceAndProblem) {
  EXPECT_EQ(parseError("vsglCount = 64\nvsglCont = 64"), "test.txt:2: vsglCont: unknown key");
  EXPECT_EQ(parseError("kernelScale = big"), "test.txt:1: kernelScale: 'big' is not a number");
  EXPECT_EQ(parseError("vsglCount = 1.5"), "test.txt:1: vsglCount: '1.5' is not an integer");
  EXPECT_EQ(parseError("vsglCount = -3"), "test.txt:1: vsglCount: -3 is outside [1, 32768]");
  EXPECT_EQ(parseError("ism.mapSize = 512"), "test.txt:1: ism.mapSize: 512 is outside [16, 256]");
  EXPECT_EQ(parseError("environment.wardAnisotropy = 0.001"),
            "test.txt:1: environment.wardAnisotropy: 0.001 is outside [0.01, 100]");
  EXPECT_EQ(parseError("brsm.fluxMix = 0"), "test.txt:1: brsm.fluxMix: 0 is outside (0, 1]");
  EXPECT_EQ(parseError("culling.budget = nan"),
            "test.txt:1: culling.budget: nan is outside [0, 0.5]");
  EXPECT_EQ(parseError("rsmSize = 300"), "test.txt:1: rsmSize: 300 is not a power of two");
  EXPECT_EQ(parseError("method = kmeans"),
            "test.txt:1: method: 'kmeans' is not one of fis, kmeans-2d, kmeans-3d, vpl");
  EXPECT_EQ(parseError("glossy = yes"), "test.txt:1: glossy: 'yes' is not one of on, off");
  EXPECT_EQ(parseError("# x\nrule = tok15\n\nrule = modified"),
            "test.txt:4: rule: duplicate key (first on line 2)");
  EXPECT_EQ(parseError("vsglCount 64"), "test.txt:1: vsglCount 64: expected 'key = value'");
  EXPECT_EQ(parseError("= 64"), "test.txt:1: '': expected 'key = value'");
  EXPECT_EQ(parseError("vsglCount ="), "test.txt:1: vsglCount: missing value");
  // Fields that disagree with each other: validateSettings's line, after the source.
  EXPECT_EQ(parseError("vsglCount = 16\nkernelScale = 32"),
            "test.txt: Settings.kernelScale: 32.000000 is outside [1, vsglCount = 16]");
  EXPECT_EQ(parseError("environment.method = sg\nenvironment.brdf = ward"),
            "test.txt: " + gi::validateSettings([] {
              gi::Settings s;
              s.environment.method = gi::EnvironmentMethod::SgLights;
              s.environment.brdf = gi::EnvironmentBrdf::Ward;
              return s;
            }()));
  // The base's own values count too: a smaller RSM needs a grid that fits it.
  EXPECT_EQ(parseError("rsmSize = 16").rfind("test.txt: Settings.brsm: ", 0), 0u);
}

TEST(SettingsFields, FilesAreReadByPath) {
  const std::string dir = std::string(VSGL_TEST_DATA) + "/settings";
  const gi::Settings s = samples::readSettingsFile(dir + "/small.txt");
  EXPECT_EQ(s.rsmSize, 64u);
  EXPECT_EQ(s.vsglCount, 32u);
  try {
    samples::readSettingsFile(dir + "/bad_range.txt");
    FAIL() << "bad_range.txt was read";
  } catch (const engine::Error& e) {
    EXPECT_EQ(std::string(e.what()),
              dir + "/bad_range.txt:4: ism.mapSize: 512 is outside [16, 256]");
  }
  for (const std::string& path : {dir + "/missing.txt", dir}) {
    try {
      samples::readSettingsFile(path);
      FAIL() << path << " was read";
    } catch (const engine::Error& e) {
      EXPECT_EQ(std::string(e.what()), path + ": cannot read");
    }
  }
}

}  // namespace
