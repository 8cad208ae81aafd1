#include "engine/view.h"

#include <algorithm>
#include <cmath>

namespace engine {

glm::mat4 perspectiveVulkan(float yfov, float aspect, float znear, float zfar) {
  float f = 1.0f / std::tan(0.5f * yfov);
  glm::mat4 p(0.0f);
  p[0][0] = f / aspect;
  p[1][1] = -f;  // NDC y down
  p[2][3] = -1.0f;
  if (zfar > 0.0f) {
    p[2][2] = zfar / (znear - zfar);
    p[3][2] = znear * zfar / (znear - zfar);
  } else {
    p[2][2] = -1.0f;
    p[3][2] = -znear;
  }
  return p;
}

glm::mat4 orthographicVulkan(float xmag, float ymag, float znear, float zfar) {
  glm::mat4 p(1.0f);
  p[0][0] = 1.0f / xmag;
  p[1][1] = -1.0f / ymag;
  p[2][2] = -1.0f / (zfar - znear);
  p[3][2] = -znear / (zfar - znear);
  return p;
}

glm::mat4 lookAlong(const glm::vec3& eye, const glm::vec3& forward, const glm::vec3& up) {
  glm::vec3 f = glm::normalize(forward);
  glm::vec3 s = glm::normalize(glm::cross(f, up));
  glm::vec3 u = glm::cross(s, f);
  glm::mat4 m(1.0f);
  m[0][0] = s.x;
  m[1][0] = s.y;
  m[2][0] = s.z;
  m[0][1] = u.x;
  m[1][1] = u.y;
  m[2][1] = u.z;
  m[0][2] = -f.x;
  m[1][2] = -f.y;
  m[2][2] = -f.z;
  m[3][0] = -glm::dot(s, eye);
  m[3][1] = -glm::dot(u, eye);
  m[3][2] = glm::dot(f, eye);
  return m;
}

View makeView(const glm::mat4& view, const glm::mat4& proj, uint32_t width, uint32_t height) {
  View v;
  v.view = view;
  v.proj = proj;
  v.viewProj = proj * view;
  v.invViewProj = glm::inverse(v.viewProj);
  v.width = width;
  v.height = height;
  return v;
}

RelativeUnprojection relativeUnprojection(const View& view) {
  glm::dmat4 rotation(view.view);
  rotation[3] = glm::dvec4(0.0, 0.0, 0.0, 1.0);
  const glm::dmat4 inverseView = glm::inverse(glm::dmat4(view.view));
  return {glm::mat4(glm::inverse(glm::dmat4(view.proj) * rotation)), glm::vec3(inverseView[3])};
}

glm::vec3 upVectorFor(const glm::vec3& forward) {
  return std::abs(forward.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

DepthRange enclosingDepthRange(const Bounds& b, const glm::vec3& eye) {
  glm::vec3 c = 0.5f * (b.min + b.max);
  float radius = 0.5f * glm::length(b.max - b.min);
  float farthest = glm::length(c - eye) + radius;
  // NDC depth resolves distance d to about d^2 / znear * 6e-8: a near plane at 1 % of the far
  // distance keeps light-view positions to ~1e-5 of the scene size (geometry within that 1 % of
  // a light is neither seen by its RSM nor casts shadows in its shadow map).
  return {std::max(1e-3f, 1e-2f * farthest), farthest * 1.01f + 1e-3f};
}

EnclosingOrtho enclosingOrthographic(const Bounds& bounds, const glm::vec3& direction) {
  glm::vec3 d = glm::normalize(direction);
  glm::vec3 c = 0.5f * (bounds.min + bounds.max);
  float radius = std::max(1e-3f, 0.5f * glm::length(bounds.max - bounds.min));
  glm::vec3 eye = c - d * (2.0f * radius);
  return {lookAlong(eye, d, upVectorFor(d)),
          orthographicVulkan(radius, radius, 0.5f * radius, 3.5f * radius), eye, radius};
}

View cameraView(const Camera& camera, uint32_t width, uint32_t height) {
  // Strip scale from the camera's node transform: only its rotation and position matter.
  glm::mat4 m = camera.cameraToWorld;
  glm::vec3 x = glm::normalize(glm::vec3(m[0])), y = glm::vec3(m[1]);
  y = glm::normalize(y - glm::dot(y, x) * x);
  glm::vec3 z = glm::cross(x, y);
  glm::mat4 rigid(glm::vec4(x, 0.0f), glm::vec4(y, 0.0f), glm::vec4(z, 0.0f), m[3]);
  glm::mat4 view = glm::inverse(rigid);
  float aspect = camera.aspectRatio > 0.0f ? camera.aspectRatio
                                           : static_cast<float>(width) / static_cast<float>(height);
  glm::mat4 proj = camera.perspective
                       ? perspectiveVulkan(camera.yfov, aspect, camera.znear, camera.zfar)
                       : orthographicVulkan(camera.xmag, camera.ymag, camera.znear, camera.zfar);
  return makeView(view, proj, width, height);
}

}  // namespace engine
