#include "engine/error.h"

namespace engine {

std::string joinLines(const std::string& text) {
  std::string out;
  bool pendingSeparator = false;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      pendingSeparator = !out.empty();
      continue;
    }
    if (pendingSeparator) {
      out += "; ";
      pendingSeparator = false;
    }
    out += c;
  }
  return out;
}

}  // namespace engine
