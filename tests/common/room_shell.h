// The shell of a box-shaped room for planner tests: the triangles that lie on a face of the
// scene's bounds and face into it, without what stands inside (the Cornell box's boxes, whose
// bottoms lie on the floor's plane but face down). Seen from inside, nothing in a shell can block
// light between two of its surfaces.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

#include "engine/scene.h"

namespace testing_gpu {

// `openTop` also leaves out the face at the top of the bounds (+y, the ceiling).
inline engine::Scene roomShell(const engine::Scene& scene, bool openTop) {
  engine::Scene room = scene;
  const engine::Bounds b = scene.bounds();
  room.indices.clear();
  room.triangleMaterial.clear();
  for (uint32_t t = 0; t < scene.triangleCount(); ++t) {
    const glm::vec3 p[3] = {scene.positions[scene.indices[3 * t]],
                            scene.positions[scene.indices[3 * t + 1]],
                            scene.positions[scene.indices[3 * t + 2]]};
    const glm::vec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
    bool wall = false;
    for (int axis = 0; axis < 3; ++axis)
      for (float side : {-1.0f, 1.0f}) {
        if (openTop && axis == 1 && side > 0.0f) continue;
        const float plane = side < 0.0f ? b.min[axis] : b.max[axis];
        bool on = -side * n[axis] > 0.999f;
        for (const glm::vec3& q : p) on = on && std::abs(q[axis] - plane) < 1e-4f;
        wall = wall || on;
      }
    if (!wall) continue;
    for (int k = 0; k < 3; ++k) room.indices.push_back(scene.indices[3 * t + k]);
    room.triangleMaterial.push_back(scene.triangleMaterial[t]);
  }
  return room;
}

}  // namespace testing_gpu
