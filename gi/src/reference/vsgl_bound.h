// The CPU twin of shaders/common/vsgl_bound.glsl, in double: a conservative upper bound of the
// light one VSGL lobe can give any receiver of a group (docs/techniques/vsgl-culling.md), and
// the group's description as vsgl_shade.comp builds it from a subgroup's pixels.
#pragma once

#include <span>

#include "reference/vsgl_shade_reference.h"
#include "shared/vsgl.h"

namespace gi {

// What the bound needs of a group of receivers (shaders/common/vsgl_bound.glsl VsglReceivers).
struct VsglReceivers {
  glm::dvec3 centre{0.0};  // bounding sphere of the positions
  double radius = 0.0;
  glm::dvec3 normalAxis{0.0, 0.0, 1.0};  // a cone holding every normal
  double normalAngle = 0.0;              // its half-angle, radians (pi: no cone)
  double albedo = 0.0;                   // largest diffuse albedo channel
  double fresnel = 0.0;                  // largest F0 channel or F90; 0 without the glossy term
  double alpha = 1.0;                    // smallest GGX alpha, max(r^2, 1e-3)
  double viewCosine = 1.0;               // smallest n . v, clamped to 1e-4
  double specularAlbedo = 0.0;  // largest specular albedo (ggxSpecularAlbedo); 0 without glossy
};

// The group of `receivers` as vsgl_shade.comp builds it: the box's centre and half-diagonal,
// the normalised sum of the normals and the widest angle from it (pi when the sum is ~0),
// the material and view extremes; `glossy` false gives fresnel and specularAlbedo 0.
VsglReceivers vsglReceivers(std::span<const ShadeReceiver> receivers, bool glossy);

// Upper bounds, in units of the lobe's largest power channel, of the diffuse
// rho / pi integral L(w) (w . n)^+ dw and glossy integral L(w) f_spec(w) (w . n)^+ dw terms that
// `lobe` gives any receiver of `group` (visibility 1). Exact integrals of the incoming radiance
// of sg_math.h vsglIncomingRadiance; 0 for a lobe without power.
struct VsglLobeBound {
  double diffuse = 0.0;
  double glossy = 0.0;
};
// `emission`: the lobe's emission model (vsgl_emitter.h); the default is the SG emitter.
VsglLobeBound vsglLobeBound(const gpu::VsglLobe& lobe, const VsglReceivers& group,
                            const VsglLobeEmission& emission = {});

}  // namespace gi
