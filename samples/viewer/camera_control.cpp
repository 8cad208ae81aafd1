#include "camera_control.h"

#include <algorithm>
#include <cmath>

namespace viewer {
namespace {

// Pitch stays short of the poles, where the view's up vector would turn with the yaw.
constexpr float kMaxPitch = 1.55f;

}  // namespace

void CameraControl::reset(const engine::Camera& camera, const engine::Bounds& bounds) {
  base_ = camera;
  moved_ = false;
  eye_ = glm::vec3(camera.cameraToWorld[3]);
  const glm::vec3 f = -glm::normalize(glm::vec3(camera.cameraToWorld[2]));
  yaw_ = std::atan2(-f.x, -f.z);
  pitch_ = std::asin(std::clamp(f.y, -1.0f, 1.0f));
  const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
  const float diagonal = glm::length(bounds.max - bounds.min);
  const float depth = std::max(glm::dot(centre - eye_, f), 0.1f * std::max(diagonal, 1e-3f));
  target_ = eye_ + depth * f;
  speed_ = std::max(0.25f * diagonal, 0.01f);
}

glm::vec3 CameraControl::forward() const {
  return {-std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
}

glm::vec3 CameraControl::right() const {
  return {std::cos(yaw_), 0.0f, -std::sin(yaw_)};
}

void CameraControl::turn(float yawDegrees, float pitchDegrees) {
  const float distance = glm::length(target_ - eye_);
  yaw_ += glm::radians(yawDegrees);
  pitch_ = std::clamp(pitch_ + glm::radians(pitchDegrees), -kMaxPitch, kMaxPitch);
  if (mode == Mode::Orbit)
    eye_ = target_ - distance * forward();
  else
    target_ = eye_ + distance * forward();
  moved_ = true;
}

void CameraControl::zoom(float factor) {
  if (mode == Mode::Orbit) {
    eye_ = target_ - factor * glm::length(target_ - eye_) * forward();
  } else {
    const glm::vec3 step = (factor - 1.0f) * speed_ * forward();
    eye_ -= step;
    target_ -= step;
  }
  moved_ = true;
}

void CameraControl::move(const glm::vec3& d) {
  const glm::vec3 up = glm::cross(right(), forward());
  const glm::vec3 step = d.x * right() + d.y * up + d.z * forward();
  eye_ += step;
  target_ += step;
  moved_ = true;
}

engine::Camera CameraControl::camera() const {
  if (!moved_) return base_;
  engine::Camera c = base_;
  const glm::vec3 z = -forward(), x = glm::normalize(glm::cross(glm::vec3(0, 1, 0), z));
  // Rigid to float precision, so that a screenshot's .gltf reads back as this very camera.
  const glm::mat4 frame =
      *engine::rigidCameraFrame(glm::mat4(glm::vec4(x, 0.0f), glm::vec4(glm::cross(z, x), 0.0f),
                                          glm::vec4(z, 0.0f), glm::vec4(eye_, 1.0f)));
  c.cameraToWorld = frame;
  return c;
}

}  // namespace viewer
