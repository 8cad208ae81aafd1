// Lets one header declare a struct for both C++ and GLSL. Rules for shared structs (std430):
// no bool, no bare vec3 (pad to vec4; a vec3 only when a 4-byte scalar follows it in its 16
// bytes, where std430 and C++ both put it, with a SHARED_ASSERT_OFFSET on that scalar), 16-byte
// aligned vec4/mat4 members first; every struct gets a SHARED_ASSERT_SIZE so a layout drift
// fails the C++ build instead of corrupting a buffer.
#ifndef SHADERS_SHARED_INTEROP_H
#define SHADERS_SHARED_INTEROP_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#define SHARED_BEGIN namespace gpu {
#define SHARED_END }
namespace gpu {
using uint = uint32_t;
using glm::ivec2;
using glm::ivec4;
using glm::mat4;
using glm::min;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
}  // namespace gpu
#define SHARED_INLINE inline
#define SHARED_ASSERT_SIZE(type, bytes) static_assert(sizeof(gpu::type) == (bytes), #type " layout")
#define SHARED_ASSERT_OFFSET(type, member, bytes) \
  static_assert(offsetof(gpu::type, member) == (bytes), #type "." #member " offset")
#else
#define SHARED_BEGIN
#define SHARED_END
#define SHARED_INLINE
#define SHARED_ASSERT_SIZE(type, bytes)
#define SHARED_ASSERT_OFFSET(type, member, bytes)
#endif

#endif
