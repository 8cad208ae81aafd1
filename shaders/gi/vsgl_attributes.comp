#version 460
// RSM -> level 0 of the six VSGL attribute pyramids (layout: shaders/shared/vsgl_attributes.h).
// Every VPL contributes its diffuse and its glossy lobe as weighted sums (vsgl-math.md 3.2):
// power, w y, w |y|^2 and w r xi, with w = luminance of the lobe's power. The CPU twin is
// gi/src/reference/vsgl_attributes_reference.cpp.
//
// kSpecular off (no surface has a specular lobe: VsglAttributes keeps the specular pyramids
// zero) skips the glossy lobe and leaves the specular images unwritten; the diffuse images are
// the same to the bit (their specular weight was an exact 0).
#extension GL_GOOGLE_include_directive : require

#include "shared/vsgl.h"
#include "shared/vsgl_attributes.h"
#include "shared/vsgl_attributes_pass.h"
#include "common/color.glsl"
#include "common/octahedral.glsl"
#include "common/vsgl_lobes.glsl"

layout(local_size_x = VSGL_ATTR_GROUP_X, local_size_y = VSGL_ATTR_GROUP_Y) in;

layout(binding = 0, rgba32f) uniform readonly image2D rsmPosition;
layout(binding = 1, rgba32f) uniform readonly image2D rsmDiffuse;
layout(binding = 2, rgba32f) uniform readonly image2D rsmSpecular;
layout(binding = 3, rg16_snorm) uniform readonly image2D rsmNormal;
// Bindings 4 + VSGL_ATTR_*: level 0 of each attribute pyramid.
layout(binding = 4 + VSGL_ATTR_DIFFUSE_POWER, rgba32f) uniform writeonly image2D outDiffusePower;
layout(binding = 4 + VSGL_ATTR_DIFFUSE_POSITION, rgba32f) uniform writeonly image2D outDiffusePosition;
layout(binding = 4 + VSGL_ATTR_DIFFUSE_AXIS, rgba32f) uniform writeonly image2D outDiffuseAxis;
layout(binding = 4 + VSGL_ATTR_SPECULAR_POWER, rgba32f) uniform writeonly image2D outSpecularPower;
layout(binding = 4 + VSGL_ATTR_SPECULAR_POSITION, rgba32f) uniform writeonly image2D outSpecularPosition;
layout(binding = 4 + VSGL_ATTR_SPECULAR_AXIS, rgba32f) uniform writeonly image2D outSpecularAxis;
layout(push_constant) uniform Push { VsglAttributesPush pc; };
layout(constant_id = 0) const bool kSpecular = true;

bool finite4(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, pc.size))) return;
  ivec2 coord = ivec2(texel);
  vec4 position = imageLoad(rsmPosition, coord);
  vec4 diffuse = imageLoad(rsmDiffuse, coord);
  vec4 specular = imageLoad(rsmSpecular, coord);
  vec3 n = octDecode(imageLoad(rsmNormal, coord).rg);
  vec4 out_[VSGL_ATTR_COUNT] = vec4[](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
  // A texel without power, or with any non-finite input, contributes nothing: one bad texel
  // must not poison the mip pyramid (vsgl-math.md section 12, case 14).
  bool valid = position.w > 0.0 && finite4(position) && finite4(diffuse) && finite4(specular);
  if (valid) {
    vec3 y = position.xyz;
    float yy = dot(y, y);
    vec3 toLight = pc.perspective != 0u ? -normalize(y) : -pc.axis.xyz;
    // The PDF weighs the texel's whole power, whichever lobe carries it.
    float pdf = luminance(diffuse.rgb) + (kSpecular ? luminance(specular.rgb) : 0.0);
    vec3 specAxis = n;
    float specSharpness = 0.0;
    if (kSpecular) vplSpecularLobe(n, toLight, specular.a, specAxis, specSharpness);
    // A broad reflection is emitted with the diffuse lobe (vplGlossyShare), unless the host
    // keeps every reflection glossy (gi::Settings::broadReflections off).
    float share = pc.broadReflections != 0u ? vplGlossyShare(specSharpness) : 1.0;
    vec3 glossy = kSpecular ? share * specular.rgb : vec3(0.0);
    vec3 lambert = diffuse.rgb + (kSpecular ? specular.rgb - glossy : vec3(0.0));
    float wd = luminance(lambert);
    float ws = luminance(glossy);
    out_[VSGL_ATTR_DIFFUSE_POWER] = vec4(lambert, wd);
    out_[VSGL_ATTR_DIFFUSE_POSITION] = vec4(wd * y, wd * yy);
    out_[VSGL_ATTR_DIFFUSE_AXIS] = vec4(wd * float(VSGL_DIFFUSE_LOBE_LENGTH) * n, pdf);
    if (kSpecular) {
      float rs = banerjeeMeanLength(specSharpness);
      out_[VSGL_ATTR_SPECULAR_POWER] = vec4(glossy, ws);
      out_[VSGL_ATTR_SPECULAR_POSITION] = vec4(ws * y, ws * yy);
      out_[VSGL_ATTR_SPECULAR_AXIS] = vec4(ws * rs * specAxis, 0.0);
    }
  }
  imageStore(outDiffusePower, coord, out_[VSGL_ATTR_DIFFUSE_POWER]);
  imageStore(outDiffusePosition, coord, out_[VSGL_ATTR_DIFFUSE_POSITION]);
  imageStore(outDiffuseAxis, coord, out_[VSGL_ATTR_DIFFUSE_AXIS]);
  if (kSpecular) {
    imageStore(outSpecularPower, coord, out_[VSGL_ATTR_SPECULAR_POWER]);
    imageStore(outSpecularPosition, coord, out_[VSGL_ATTR_SPECULAR_POSITION]);
    imageStore(outSpecularAxis, coord, out_[VSGL_ATTR_SPECULAR_AXIS]);
  }
}
