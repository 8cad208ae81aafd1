// How every sample program ends: one "<program>: error: <message>" line on stderr and exit
// status 1 for any error, including validation-layer messages during a successful run.
#pragma once

#include <cstdio>
#include <exception>

#include "engine/vk_context.h"

namespace samples {

// 0, or 1 after the error line when the validation layer reported anything.
int validationExitStatus(const engine::Context& ctx, const char* program);

// Runs `body` (returning the exit status); an exception becomes the error line and status 1.
template <class Body>
int guardedMain(const char* program, Body body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace samples
