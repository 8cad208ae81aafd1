#include "cli_values.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

#include "engine/error.h"

namespace samples {

void parseCommonOption(std::string_view arg, Arguments& args, CommonOptions& o) {
  if (arg == "--device")
    o.device = args.value();
  else if (arg == "--validation")
    o.validation = true;
  else if (arg == "--help" || arg == "-h")
    o.help = true;
  else
    throw engine::Error(std::string(arg) + ": unknown option (see --help)");
}

uint32_t parseUint(std::string_view option, std::string_view text, uint32_t lo, uint32_t hi) {
  uint32_t value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi)
    throw engine::Error(std::string(option) + ": expected an integer in [" + std::to_string(lo) +
                        ", " + std::to_string(hi) + "], got '" + std::string(text) + "'");
  return value;
}

float parseFloat(std::string_view option, std::string_view text, float lo, float hi) {
  std::string s(text);
  char* end = nullptr;
  float value = std::strtof(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(value) || value < lo || value > hi)
    throw engine::Error(std::string(option) + ": expected a number in [" + std::to_string(lo) +
                        ", " + std::to_string(hi) + "], got '" + s + "'");
  return value;
}

std::vector<std::string> parseList(std::string_view option, std::string_view text) {
  std::vector<std::string> words;
  for (size_t start = 0;;) {
    const size_t comma = std::min(text.find(',', start), text.size());
    if (comma == start)
      throw engine::Error(std::string(option) + ": empty item in '" + std::string(text) + "'");
    words.emplace_back(text.substr(start, comma - start));
    if (comma == text.size()) return words;
    start = comma + 1;
  }
}

std::vector<uint32_t> parseUintList(std::string_view option, std::string_view text, uint32_t lo,
                                    uint32_t hi) {
  std::vector<uint32_t> values;
  for (const std::string& word : parseList(option, text))
    values.push_back(parseUint(option, word, lo, hi));
  return values;
}

}  // namespace samples
