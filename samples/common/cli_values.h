// Parsing of option values for the sample programs: each bad value becomes an engine::Error
// naming the option, the accepted range and what was typed.
#pragma once

#include <cstdint>
#include <string_view>

namespace samples {

uint32_t parseUint(std::string_view option, std::string_view text, uint32_t lo, uint32_t hi);
float parseFloat(std::string_view option, std::string_view text, float lo, float hi);

}  // namespace samples
