// Every field of gi::Settings (gi/include/gi/settings.h) in one table: its key (the C++ member
// path), group, unit, range, kind and accessors, and "key = value" text files of settings read
// and written through it. The sample programs and tools take settings from this one table
// instead of an option per field, so a new field in settings.h needs one row here (the unit
// test test_settings_fields.cpp counts the members of every settings struct against it).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gi/settings.h"

namespace samples {

struct SettingField {
  enum class Kind { Uint, Int, Float, Bool, Choice };
  // The heading settings.h groups the field under: "VSGLs", "k-means", "BRSM", "ISM", "Planner",
  // "Adaptive shading", "Culling", "Environment" or "Debug".
  const char* group;
  const char* key;   // the C++ path: "vsglCount", "brsm.gridSize", "environment.method"
  const char* unit;  // "" or "m", "rad", "texels", "VSGLs", "points", ...
  const char* help;  // one line: what it does or costs (settings.h has the whole story)
  Kind kind;
  // Inclusive range as settings.h states it for the field alone (Bool 0..1, Choice 0..n-1);
  // limits that depend on another field (vsglCount <= maxVsglCount, ...) are left to
  // gi::validateSettings. Float bounds are the float values validateSettings compares with.
  double min = 0.0;
  double max = 1.0;
  bool powerOfTwo = false;
  // A "Creation." field: changing it means creating a new IndirectLighting.
  bool creation = false;
  // Choice: each word and the enum value it stands for, e.g. {"modified", 1}, {"tok15", 0}.
  std::vector<std::pair<const char*, uint32_t>> choices;
  // The field's value as a double (exact for every field's type) and its inverse.
  double (*get)(const gi::Settings&) = nullptr;
  void (*set)(gi::Settings&, double) = nullptr;
};

// Every field, grouped as above, in the order files are written.
const std::vector<SettingField>& settingFields();
// The field whose key is `key`, or nullptr.
const SettingField* findSettingField(std::string_view key);

// "key = value" lines, one per field in table order, after the comment line
// "# gi::Settings (samples/common/settings_fields.h)". Values are written exactly: floats as the
// shortest text that reads back as the same float, choices as their words, bools as on/off.
std::string formatSettings(const gi::Settings& s);

// Reads such text: '#' starts a comment, blank lines are skipped, any subset of the keys may be
// given and the other fields keep `base`'s values. Throws engine::Error with one line,
// "<source>:<line>: <key>: <problem>" (unknown key, bad number, out of range, not a power of
// two, unknown word (naming the accepted ones), duplicate key), or "<source>: " and
// gi::validateSettings's message when the fields disagree with each other.
gi::Settings parseSettings(std::string_view text, const std::string& source,
                           const gi::Settings& base = {});
// parseSettings of a file's contents, named by its path; "<path>: cannot read" when it cannot be.
gi::Settings readSettingsFile(const std::string& path, const gi::Settings& base = {});

}  // namespace samples
