// The viewer's camera: an orbit about a target (drag to turn, wheel to zoom) or a fly camera
// (drag to look, WASD/QE to move). It starts as the scene's camera and stays exactly that camera
// until it is moved, so that an untouched view is the one vsgl_render renders. World +y is up
// once it moves (a rolled glTF camera loses its roll).
#pragma once

#include <glm/glm.hpp>

#include "engine/scene.h"

namespace viewer {

class CameraControl {
 public:
  enum class Mode { Orbit, Fly };

  // Starts from `camera`; the orbit's target is the point of `bounds`'s centre's depth on the
  // view axis (at least 10 % of the bounds' diagonal away).
  void reset(const engine::Camera& camera, const engine::Bounds& bounds);

  // Orbit: the eye turns about the target, degrees (yaw about +y, pitch up). Fly: the view
  // turns about the eye.
  void turn(float yawDegrees, float pitchDegrees);
  // Orbit: the distance to the target times `factor`; fly: forward by (factor - 1) x speed.
  void zoom(float factor);
  // Moves eye and target along the view's right, up and forward axes, metres.
  void move(const glm::vec3& rightUpForward);

  Mode mode = Mode::Orbit;
  engine::Camera camera() const;
  glm::vec3 eye() const { return eye_; }
  glm::vec3 forward() const;
  glm::vec3 right() const;
  float speed() const { return speed_; }  // metres per second of a held key, from the scene

 private:
  engine::Camera base_;
  bool moved_ = false;
  glm::vec3 eye_{0.0f}, target_{0.0f};
  float yaw_ = 0.0f, pitch_ = 0.0f;  // radians of the view direction; yaw 0 looks down -z
  float speed_ = 1.0f;
};

}  // namespace viewer
