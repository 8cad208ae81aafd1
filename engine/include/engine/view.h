// View and projection matrices in this project's conventions: right-handed world, camera looks
// down its -Z, Vulkan clip space with NDC y pointing down (row 0 is the top of the image) and
// depth in [0, 1] (near = 0). GLM column-major matrices, column vectors (clip = P * V * x).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "engine/scene.h"

namespace engine {

struct View {
  glm::mat4 view{1.0f};  // world -> camera
  glm::mat4 proj{1.0f};  // camera -> clip
  glm::mat4 viewProj{1.0f};
  glm::mat4 invViewProj{1.0f};
  uint32_t width = 0;
  uint32_t height = 0;
};

// Perspective projection; zfar = 0 gives an infinite far plane (depth -> 1 at infinity).
glm::mat4 perspectiveVulkan(float yfov, float aspect, float znear, float zfar);
// Orthographic projection of the box [-xmag, xmag] x [-ymag, ymag] x [-zfar, -znear].
glm::mat4 orthographicVulkan(float xmag, float ymag, float znear, float zfar);
// World -> camera for a camera at `eye` looking along `forward` (any `up` not parallel to it).
glm::mat4 lookAlong(const glm::vec3& eye, const glm::vec3& forward, const glm::vec3& up);

// The camera's view for a width x height image. The camera's aspect ratio, when set, wins
// over the image's (pixels are then non-square, as glTF specifies).
View cameraView(const Camera& camera, uint32_t width, uint32_t height);

View makeView(const glm::mat4& view, const glm::mat4& proj, uint32_t width, uint32_t height);

// Unprojection relative to the eye: invViewProjRelative maps NDC to the offset from `eye`
// (the inverse of projection x rotation, in double, rounded once). Rebuilding a world position
// as eye + offset keeps it accurate far from the world origin, where the full inverse
// view-projection cancels terms of size |eye| / znear (docs/techniques/stability.md, case 6).
struct RelativeUnprojection {
  glm::mat4 invViewProjRelative{1.0f};
  glm::vec3 eye{0.0f};
};
RelativeUnprojection relativeUnprojection(const View& view);

// An up vector not parallel to `forward`, for views placed by code (lights).
glm::vec3 upVectorFor(const glm::vec3& forward);

// Near and far planes for a light view from `eye` that encloses the whole of `bounds` (near at
// 1 % of the far distance: see view.cpp for the depth-precision trade).
struct DepthRange {
  float znear;
  float zfar;
};
DepthRange enclosingDepthRange(const Bounds& bounds, const glm::vec3& eye);

// An orthographic view looking along `direction` that encloses `bounds`: eye two bounding
// radii before the centre, a square window one radius wide on each side.
struct EnclosingOrtho {
  glm::mat4 view;
  glm::mat4 proj;
  glm::vec3 eye;
  float halfExtent;  // metres
};
EnclosingOrtho enclosingOrthographic(const Bounds& bounds, const glm::vec3& direction);

}  // namespace engine
