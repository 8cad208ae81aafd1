// The brute-force VPL gather (issue 5): every texel of the bouncing light's RSM as a virtual
// point light carrying the texel's incident power and its surface's diffuse and GGX lobes,
// summed at every camera pixel with an exact visibility ray per pixel-VPL pair. It is what the
// VSGLs approximate (the same RSM, through the CPU twins of the RSM passes), so its gap to the
// path tracer is the RSM's own error and its gap to the VSGL image is the VSGLs'.
//
// A VPL is the texel's patch of area A: its radiance towards x is f_y(l, w) Phi / A, so its
// intensity is f_y(l, w) Phi cos_y, and the receiver gets f_x(w, v) cos_x I / d^2. The 1/d^2 of
// a point is replaced by the on-axis form factor of a disc of area A, 1 / (d^2 + A / pi): the same
// far away, bounded where a receiver touches the VPL, and converging to the exact integral as the
// RSM is refined (no clamping constant to tune). For the same reason both GGX lobes, the VPL's
// and the receiver's, are widened by the patch's angular size seen from the receiver
// (alpha^2 + A / (4 pi d^2)), so a near-mirror surface does not turn a VPL into a spike.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "embree_scene.h"
#include "engine/scene.h"
#include "engine/view.h"

namespace truth {

struct Vpl {
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};           // shading normal, facing the light
  glm::dvec3 geometricNormal{0.0};  // of the triangle it lies on, facing the light
  glm::dvec3 toLight{0.0};          // unit direction from the VPL to the light
  glm::dvec3 incident{0.0};         // Phi_in per channel, W
  double area = 0.0;                // the texel's patch, m^2
  glm::dvec3 diffuse{0.0};          // albedo
  glm::dvec3 f0{0.0};
  double f90 = 1.0;
  double roughness = 0.0;
  uint32_t texel = 0;  // view * rsmSize^2 + y * rsmSize + x of the RSM texel it stands for
};

// The lit texels of light `light`'s rsmSize^2 RSM views (gi::makeRsmViews: one, or a point
// light's six cube faces, numbered in that order), rasterised and resolved by the CPU references,
// flux by gi::rsmFluxReference, each moved onto the surface `rays` finds along the light's ray
// through it.
std::vector<Vpl> rsmVpls(const engine::Scene& scene, const EmbreeScene& rays, uint32_t light,
                         uint32_t rsmSize);
// Those of every light in `lights`, one after the other (their gather is the sum of each one's).
// Texels are numbered across all their views in order, view v's from v * rsmSize^2 (a point
// light has six views), as the module's FrameOutput::vsglViews lists them.
std::vector<Vpl> rsmVpls(const engine::Scene& scene, const EmbreeScene& rays,
                         std::span<const uint32_t> lights, uint32_t rsmSize);

struct VplGatherImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::dvec3> diffuse;  // through the receiver's Lambert lobe, W sr^-1 m^-2
  std::vector<glm::dvec3> glossy;   // through its GGX lobe
  size_t vplCount = 0;
  double seconds = 0.0;
};

// Primary rays through pixel centres, as the path tracer's. `threads` 0: every core.
// `visibility` false: no visibility rays (the error budget's unshadowed stages).
VplGatherImage vplGather(const engine::Scene& scene, const EmbreeScene& rays,
                         const engine::View& view, const std::vector<Vpl>& vpls,
                         unsigned threads = 0, bool visibility = true);

}  // namespace truth
