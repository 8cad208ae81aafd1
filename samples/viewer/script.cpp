#include "script.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "engine/error.h"
#include "frame_request.h"
#include "options.h"
#include "settings_fields.h"

namespace viewer {
namespace {

enum class Args { Numbers, Word, KeyValue };
struct Shape {
  Args kind;
  size_t count;
};
const std::map<std::string, Shape>& commands() {
  static const std::map<std::string, Shape> table = {
      {"orbit", {Args::Numbers, 2}},      {"zoom", {Args::Numbers, 1}},
      {"move", {Args::Numbers, 3}},       {"light", {Args::Numbers, 1}},
      {"light-move", {Args::Numbers, 3}}, {"light-turn", {Args::Numbers, 2}},
      {"set", {Args::KeyValue, 2}},       {"view", {Args::Word, 1}},
      {"split", {Args::Word, 1}},         {"pick", {Args::Numbers, 2}},
      {"screenshot", {Args::Word, 1}},    {"scene", {Args::Word, 1}},
      {"environment", {Args::Word, 1}},
  };
  return table;
}

bool parseNumber(const std::string& text, float& value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

}  // namespace

float scriptNumber(const ScriptEvent& event, size_t i) {
  float value = 0.0f;
  parseNumber(event.args.at(i), value);
  return value;
}

std::vector<ScriptEvent> readScript(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw engine::Error(path + ": cannot read");
  std::vector<ScriptEvent> events;
  std::string text;
  for (uint32_t line = 1; std::getline(in, text); ++line) {
    auto fail = [&](const std::string& problem) {
      throw engine::Error(path + ":" + std::to_string(line) + ": " + problem);
    };
    if (const size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    std::string frame;
    if (!(words >> frame)) continue;
    ScriptEvent e;
    e.line = line;
    unsigned long value = 0;
    auto [ptr, ec] = std::from_chars(frame.data(), frame.data() + frame.size(), value);
    if (ec != std::errc() || ptr != frame.data() + frame.size() || value > 100000)
      fail("'" + frame + "' is not a frame number in [0, 100000]");
    e.frame = uint32_t(value);
    if (!events.empty() && e.frame < events.back().frame)
      fail("frame " + frame + " comes after frame " + std::to_string(events.back().frame));
    if (!(words >> e.command)) fail("a frame number without a command");
    const auto shape = commands().find(e.command);
    if (shape == commands().end()) fail("unknown command '" + e.command + "'");
    for (std::string arg; words >> arg;) e.args.push_back(arg);
    if (e.args.size() != shape->second.count)
      fail(e.command + " takes " + std::to_string(shape->second.count) + " argument(s), got " +
           std::to_string(e.args.size()));
    if (shape->second.kind == Args::Numbers)
      for (const std::string& a : e.args)
        if (float v; !parseNumber(a, v)) fail(e.command + ": '" + a + "' is not a finite number");
    if (e.command == "view") parseViewMode(path + ":" + std::to_string(line) + ": view", e.args[0]);
    if (e.command == "set")  // the value is checked against the field's range here
      samples::parseSettings(e.args[0] + " = " + e.args[1],
                             path + ":" + std::to_string(line) + ": set");
    if (e.command == "split" && e.args[0] != "off")
      withMethod({}, path + ":" + std::to_string(line) + ": split", e.args[0]);
    if (e.command == "zoom" && !(scriptNumber(e, 0) >= 0.1f && scriptNumber(e, 0) <= 10.0f))
      fail("zoom: the factor must lie in [0.1, 10]");
    events.push_back(std::move(e));
  }
  return events;
}

}  // namespace viewer
