// The CPU twin of vsgl_shade.comp: the indirect diffuse and glossy radiance that a receiver
// reflects toward the viewer from a set of VSGLs (vsgl-math.md section 4.5), in double with
// the oracle functions of sg_math.h. Naive on purpose: one receiver, every VSGL, both lobes.
#pragma once

#include <functional>
#include <span>

#include "reference/sg_math.h"
#include "reference/vsgl_emitter.h"
#include "shared/vsgl.h"

namespace gi {

struct ShadeReceiver {
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0, 0.0, 1.0};  // unit, facing the viewer
  glm::dvec3 view{0.0, 0.0, 1.0};    // unit, from the receiver toward the viewer
  glm::dvec3 albedo{0.0};            // diffuse albedo rho
  glm::dvec3 f0{0.0};                // Schlick F0
  double f90 = 1.0;                  // Schlick F90 (KHR_materials_specular's strength)
  double roughness = 1.0;            // perceptual; GGX alpha = max(r^2, 1e-3) as brdf.glsl
};

struct IndirectRadiance {
  glm::dvec3 diffuse{0.0};
  glm::dvec3 glossy{0.0};
};

// Visibility of VSGL `index` from the receiver, in [0, 1]; empty = 1 for every VSGL.
using VsglVisibility = std::function<double(uint32_t index)>;

// `planar`: the planar-emitter model of vsgl_emitter.h (Settings::planarEmitters).
IndirectRadiance shadeReference(const ShadeReceiver& receiver, std::span<const gpu::Vsgl> vsgls,
                                bool glossy, bool planar, const VsglVisibility& visibility = {});

}  // namespace gi
