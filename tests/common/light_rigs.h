// Lights the point-light and many-light tests add to the Cornell box (docs/techniques/
// point-lights.md, many-lights.md).
#pragma once

#include <glm/glm.hpp>

#include "engine/scene.h"

namespace testing_gpu {

// A point light in the middle of the Cornell box (1 m up) at a quarter of its spot's intensity,
// about the spot's power in the room.
inline engine::Light middlePointLight(const engine::Scene& cornell) {
  engine::Light point = cornell.lights.at(0);
  point.name = "middle point";
  point.type = engine::LightType::Point;
  point.position = glm::vec3(0.0f, 1.0f, 0.0f);
  point.intensity *= 0.25f;
  return point;
}

}  // namespace testing_gpu
