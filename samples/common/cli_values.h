// Parsing of option values for the sample programs: each bad value becomes an engine::Error
// naming the option, the accepted range and what was typed.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/error.h"

namespace samples {

// Walks a command line: `for (Arguments args(argc, argv); args.next();)`, then option() is the
// word at hand and value() consumes the next one ("<option>: missing value" when there is none).
class Arguments {
 public:
  Arguments(int argc, char** argv) : argc_(argc), argv_(argv) {}
  bool next() { return ++index_ < argc_; }
  std::string_view option() const { return argv_[index_]; }
  std::string_view value() {
    if (index_ + 1 >= argc_) throw engine::Error(std::string(option()) + ": missing value");
    return argv_[++index_];
  }

 private:
  int argc_;
  char** argv_;
  int index_ = 0;
};

// The options at the end of every sample program's command line.
struct CommonOptions {
  std::string device;       // --device SEL: index or name substring ("" = VSGL_DEVICE or automatic)
  bool validation = false;  // --validation
  bool help = false;        // --help, -h
};
// Takes `arg` (and its value) into `o`; anything else throws "<arg>: unknown option (see --help)".
void parseCommonOption(std::string_view arg, Arguments& args, CommonOptions& o);

uint32_t parseUint(std::string_view option, std::string_view text, uint32_t lo, uint32_t hi);
float parseFloat(std::string_view option, std::string_view text, float lo, float hi);
// A comma-separated list of non-empty words, e.g. --scenes cornell,atrium.
std::vector<std::string> parseList(std::string_view option, std::string_view text);
// A comma-separated list of integers, each in [lo, hi], e.g. --counts 64,256.
std::vector<uint32_t> parseUintList(std::string_view option, std::string_view text, uint32_t lo,
                                    uint32_t hi);

// One of a fixed set of words, e.g. --ism on|off; anything else names the accepted words.
template <class T>
T parseChoice(std::string_view option, std::string_view text,
              std::initializer_list<std::pair<std::string_view, T>> choices) {
  std::string accepted;
  for (const auto& [word, value] : choices) {
    if (word == text) return value;
    accepted += (accepted.empty() ? "" : ", ") + std::string(word);
  }
  throw engine::Error(std::string(option) + ": '" + std::string(text) + "' is not one of " +
                      accepted);
}

}  // namespace samples
