#include "program_exit.h"

namespace samples {

int validationExitStatus(const engine::Context& ctx, const char* program) {
  if (ctx.validationMessageCount() == 0) return 0;
  std::fprintf(stderr, "%s: error: %u validation messages\n", program,
               ctx.validationMessageCount());
  return 1;
}

}  // namespace samples
