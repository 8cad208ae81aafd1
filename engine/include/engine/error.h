// Errors that come from the environment or from user input (a bad file, no device, an absurd
// setting) are thrown as engine::Error with a one-line message naming the file or field and the
// problem; programs catch it in main, print it and exit non-zero. Bugs use assert/VK_CHECK.
#pragma once

#include <stdexcept>
#include <string>

namespace engine {

// Joins a multi-line message (as tinygltf and OpenImageIO report them) into one line, the lines
// separated by "; ", so that every engine::Error stays one line.
std::string joinLines(const std::string& text);

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace engine
