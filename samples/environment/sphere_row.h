// The scene of vsgl_environment: a row of spheres of GGX metals and dielectrics, roughness 0.1
// to 0.8 from left to right, seen level from the front (the set-up of Krivanek and Colbert 2008,
// Fig. 1, spread over one row so that every roughness is measured in one image).
#pragma once

#include <string>

#include "engine/scene.h"

namespace environment {

// The spheres' radius [m] and the distance between neighbouring centres [m]; the row is centred
// on the origin along +x, the camera looks along -z from +z.
constexpr float kSphereRadius = 0.5f;
constexpr float kSphereSpacing = 1.15f;
constexpr int kSphereCount = 5;

// UV spheres of kSphereSegments around and kSphereRings from pole to pole: at the default
// 384 x 128 a sphere spans about 70 pixels, so the facets (5.6 degrees) stay below two pixels.
constexpr int kSphereSegments = 96;
constexpr int kSphereRings = 48;

// The row as an engine::Scene: one material per sphere, per-vertex normals of the true sphere
// (so the shading normal is smooth), and one camera framing the row for an image of aspect
// `aspect` (width / height), whose vertical field of view follows from it.
engine::Scene makeSphereRow(float aspect);

// A one-line description of the materials, for the reports.
std::string sphereRowDescription();

}  // namespace environment
