// The checks FrameInput's light must pass before a frame is recorded: every value finite and in
// the range gi/include/gi/indirect_lighting.h states, so that a host's bad light comes back as a
// Status naming the field instead of NaN light or a refused RSM view.
#pragma once

#include <string>

#include "gi/indirect_lighting.h"

namespace gi {

// "" when `light` is valid, else one line naming the field (`field` + ".name") and the problem.
std::string validateLight(const Light& light, const std::string& field);

}  // namespace gi
