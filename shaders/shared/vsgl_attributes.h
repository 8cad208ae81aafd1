// The summable per-texel VSGL quantities of an RSM (vsgl-math.md sections 3.2 and 3.5), one
// RGBA32F mip pyramid each. For lobe c in {diffuse, specular} with scalar weight
// w = luminance(Phi_c) (Rec. 709) and y = VPL position minus the RSM origin:
//   VSGL_ATTR_*_POWER     rgb = Phi_c (W),      a = w
//   VSGL_ATTR_*_POSITION  xyz = w y (W m),      w = w |y|^2 (W m^2)
//   VSGL_ATTR_*_AXIS      xyz = w r xi (W),     w = PDF (only in VSGL_ATTR_DIFFUSE_AXIS; the
//                         flux-proportional PDF is w_d + w_s, the BRSM pass overwrites it)
// Mips are exact box means, so every ratio of two channels read with the same kernel is an
// exact kernel-weighted mean. Texels without power, or with any non-finite input, are all zero.
// Storage is fp32 only; fp16 is refused by design: w |y|^2 reaches ~1e11 for the intensities and
// scene scales of Tokuyoshi's demo (vsgl-math.md section 12, case 5), far past fp16's 65504.
#ifndef SHADERS_SHARED_VSGL_ATTRIBUTES_H
#define SHADERS_SHARED_VSGL_ATTRIBUTES_H

#define VSGL_ATTR_DIFFUSE_POWER 0
#define VSGL_ATTR_DIFFUSE_POSITION 1
#define VSGL_ATTR_DIFFUSE_AXIS 2
#define VSGL_ATTR_SPECULAR_POWER 3
#define VSGL_ATTR_SPECULAR_POSITION 4
#define VSGL_ATTR_SPECULAR_AXIS 5
#define VSGL_ATTR_COUNT 6

#define VSGL_ATTR_GROUP_X 8
#define VSGL_ATTR_GROUP_Y 8

#endif
