// A ray's hit turned into what the references shade: position, geometric normal and the
// surface as the G-buffer resolve decodes it (engine::surfaceAt).
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "embree_scene.h"
#include "engine/gbuffer_reference.h"
#include "engine/scene.h"
#include "engine/view.h"

namespace truth {

// A ray's hit as a shading point: the surface as the resolve decodes it, and the geometric
// normal on the side the ray came from. Embree reports fp32 barycentrics; on the large
// triangles of a floor they place the point millimetres off, so the hit is recomputed in double
// as the ray's intersection with the triangle's plane (Moller and Trumbore 1997).
struct ShadingPoint {
  glm::dvec3 position;
  glm::dvec3 geometricNormal;
  engine::GBufferSample surface;
};

// `backFaces` as the resolve: AsFront where the camera sees the point, PerMaterial where the
// point bounces a light (engine::BackFaces: the back of a single-sided material reflects none).
ShadingPoint shadingPoint(const engine::Scene& scene, const RayHit& hit, glm::dvec3 origin,
                          glm::dvec3 rayDir,
                          engine::BackFaces backFaces = engine::BackFaces::AsFront);

// What the camera sees through the centre of pixel `pixel` (row-major index) of `view`: the
// primary ray the references shade along, and its shading point; nothing on background.
struct PrimaryHit {
  engine::CameraRay ray;
  ShadingPoint point;
};
std::optional<PrimaryHit> primaryHit(const engine::Scene& scene, const EmbreeScene& rays,
                                     const engine::View& view, size_t pixel);

}  // namespace truth
