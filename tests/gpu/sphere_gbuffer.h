// An analytic G-buffer for the environment-lighting tests: a unit sphere at the origin,
// ray-traced through each pixel centre of a view and encoded as the G-buffer resolve stores it
// (NDC depth, octahedral RG16_SNORM normal, RGBA16F albedo + roughness and F0 + F90), so the
// shading under test sees exact geometry.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>

#include "engine/gbuffer.h"
#include "engine/view.h"

namespace testing_gpu {

struct SphereMaterial {
  glm::dvec3 albedo;
  double roughness;
  glm::dvec3 f0;
  double f90;
};
using SphereMaterialFunction = std::function<SphereMaterial(uint32_t x, uint32_t y)>;

// An elevated camera at (0, 1.2, 3) looking at the sphere's centre (60 % of the image across):
// a few visible normals have z < 0 and the mirror directions cover both hemispheres of z.
engine::View sphereView(uint32_t width, uint32_t height);

// The sphere seen through `view` (its size is the G-buffer's), material per pixel; background
// pixels keep depth 1. The images come back in GENERAL layout.
engine::GBuffer sphereGBuffer(engine::Context& ctx, const engine::View& view,
                              const SphereMaterialFunction& material);

}  // namespace testing_gpu
