// Colour helpers shared by the passes.
#ifndef SHADERS_COMMON_COLOR_GLSL
#define SHADERS_COMMON_COLOR_GLSL

// Rec. 709 luminance: the scalar weight of RGB powers (vsgl-math.md section 3.2); the CPU
// references use gi::luminance709 with the same weights.
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

#endif
