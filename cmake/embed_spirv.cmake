# Turns a SPIR-V binary into a C++ header: inline constexpr uint32_t k<CamelName>Spv[] = {...};
# SPIR-V words are little-endian on disk, so each group of four bytes is reversed into one word.
file(READ ${SPV} hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])"
       "0x\\4\\3\\2\\1u," body "${hex}")
string(REGEX REPLACE "((0x[0-9a-f]+u,){12})" "\\1\n" body "${body}")
string(REPLACE "_" ";" parts "${NAME}")
set(camel "")
foreach(p ${parts})
  string(SUBSTRING "${p}" 0 1 first)
  string(TOUPPER "${first}" first)
  string(SUBSTRING "${p}" 1 -1 rest)
  string(APPEND camel "${first}${rest}")
endforeach()
file(WRITE ${HEADER}.tmp "// Generated from ${NAME}.comp by cmake/embed_spirv.cmake. Do not edit.\n#pragma once\n#include <cstdint>\ninline constexpr uint32_t k${camel}Spv[] = {\n${body}};\n")
file(RENAME ${HEADER}.tmp ${HEADER})
