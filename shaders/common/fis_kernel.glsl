// What VSGL generation (vsgl_generate.comp) and the environment's SG lights
// (env_sg_generate.comp) share when they read a kernel off a mip pyramid: Vulkan's LINEAR filter
// with CLAMP_TO_EDGE, evaluated with exact weights from texelFetch (the CPU twins repeat it), its
// trilinear blend between levels, and the modified-FIS level search of [S3] Eq. 3
// (docs/vsgl-math.md section 5.3).
// The includer defines, before calling modifiedFisBisection,
//   float fisKernelMass(vec2 x, float level);
// the fraction of the PDF's mass inside a level-`level` kernel centred at x (state it needs,
// such as the pyramid's layer, travels in the includer's globals).
#ifndef COMMON_FIS_KERNEL_GLSL
#define COMMON_FIS_KERNEL_GLSL

// The four texels around x on an n x n level: i0 the top-left one, i1 the bottom-right one
// (clamped to the edge), f the weights of i1's column and row.
struct BilinearTaps {
  ivec2 i0;
  ivec2 i1;
  vec2 f;
};

BilinearTaps bilinearTaps(vec2 x, int n) {
  vec2 t = x * float(n) - 0.5;
  vec2 base = floor(t);
  return BilinearTaps(clamp(ivec2(base), ivec2(0), ivec2(n - 1)),
                      clamp(ivec2(base) + 1, ivec2(0), ivec2(n - 1)), t - base);
}

// The texels (i0.x, i0.y), (i1.x, i0.y), (i0.x, i1.y), (i1.x, i1.y) blended.
vec4 bilinearBlend(BilinearTaps b, vec4 c00, vec4 c10, vec4 c01, vec4 c11) {
  return mix(mix(c00, c10, b.f.x), mix(c01, c11, b.f.x), b.f.y);
}

// The two levels a trilinear lookup at `level` (clamped to [0, top]) blends, and the weight of
// the upper one.
void trilinearLevels(float level, int top, out int l0, out int l1, out float upper) {
  level = clamp(level, 0.0, float(top));
  float low = floor(level);
  l0 = int(low);
  l1 = min(l0 + 1, top);
  upper = level - low;
}

float fisKernelMass(vec2 x, float level);

// [S3] Eq. 3 with K: the level in [0, top] whose kernel holds `target` of the mass, by
// bisection (the mass grows with the level); 0 where one texel already holds more (a spike:
// kernels share the texel), top where even the whole map holds less (`enough` false).
float modifiedFisBisection(vec2 x, float target, float top, bool enough) {
  if (fisKernelMass(x, 0.0) >= target) return 0.0;
  if (!enough) return top;
  float lo = 0.0, hi = top;
  for (int step = 0; step < VSGL_BISECTION_STEPS; ++step) {
    float mid = 0.5 * (lo + hi);
    if (fisKernelMass(x, mid) < target) lo = mid; else hi = mid;
  }
  return 0.5 * (lo + hi);
}

#endif
