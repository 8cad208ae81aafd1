// The scene's triangles in an Intel Embree BVH, for the CPU references' rays. One device and one
// committed scene per EmbreeScene; queries are thread-safe (Embree allows concurrent
// rtcIntersect1 / rtcOccluded1 on a committed scene).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <memory>

#include "engine/scene.h"

namespace truth {

struct RayHit {
  bool hit = false;
  double t = 0.0;           // distance along the unit direction
  uint32_t triangle = 0;    // index into Scene::indices / 3
  glm::dvec2 barycentrics;  // (u, v) of vertices 1 and 2; vertex 0 has 1 - u - v
};

class EmbreeScene {
 public:
  // Throws engine::Error when Embree cannot create its device or the scene has no triangles.
  explicit EmbreeScene(const engine::Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit along origin + t dir, t in [tnear, tfar]; `dir` unit length. Embree traces in
  // fp32: callers offset origins that lie on a surface (see offsetOrigin).
  RayHit intersect(glm::dvec3 origin, glm::dvec3 dir, double tnear = 0.0,
                   double tfar = std::numeric_limits<double>::infinity()) const;
  // Whether anything lies on the segment origin + t dir, t in [tnear, tfar].
  bool occluded(glm::dvec3 origin, glm::dvec3 dir, double tnear, double tfar) const;
  // Whether the segment between two points (both already offset off their surfaces with
  // offsetOrigin) is free of geometry.
  bool visible(glm::dvec3 from, glm::dvec3 to) const;

 private:
  struct Handles;
  std::unique_ptr<Handles> handles_;
};

// A surface point moved off its own triangle along the geometric normal `ng` (unit, on the side
// the new ray leaves from), far enough that fp32 traversal cannot hit the triangle again:
// a few ulps of the point's largest coordinate.
glm::dvec3 offsetOrigin(glm::dvec3 p, glm::dvec3 ng);

}  // namespace truth
