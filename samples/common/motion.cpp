#include "motion.h"

#include <algorithm>
#include <cassert>
#include <glm/gtc/matrix_transform.hpp>
#include <utility>

#include "engine/error.h"
#include "gi_host.h"

namespace samples {
namespace {

constexpr float kOrbitDegrees = 30.0f;
constexpr float kSweepDegrees = 20.0f;

// -1/2 .. 1/2 over the sequence (0 for a single frame), so each motion is centred on the scene's
// own framing.
float phase(uint32_t t, uint32_t frames) {
  return frames > 1 ? float(t) / float(frames - 1) - 0.5f : 0.0f;
}

glm::mat4 aboutVertical(glm::vec3 centre, float degrees) {
  const glm::mat4 toOrigin = glm::translate(glm::mat4(1.0f), -centre);
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0));
  return glm::translate(glm::mat4(1.0f), centre) * turn * toOrigin;
}

// An axis-aligned box of `size` standing with its base centre at `baseCentre`, in a new diffuse
// material:
// 6 faces of 2 triangles, counter-clockwise seen from outside.
void addBox(engine::Scene& scene, glm::vec3 baseCentre, glm::vec3 size) {
  engine::Material material;
  material.name = "moving box";
  material.baseColorFactor = glm::vec4(0.8f, 0.75f, 0.7f, 1.0f);
  material.metallicFactor = 0.0f;
  material.roughnessFactor = 0.8f;
  const auto materialIndex = static_cast<uint32_t>(scene.materials.size());
  scene.materials.push_back(material);
  const glm::vec3 h = 0.5f * size;
  const glm::vec3 c = baseCentre + glm::vec3(0.0f, h.y, 0.0f);
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = sign;
      // Two tangents spanning the face, ordered so that cross(du, dv) = n.
      glm::vec3 du(0.0f), dv(0.0f);
      du[(axis + 1) % 3] = h[(axis + 1) % 3];
      dv[(axis + 2) % 3] = h[(axis + 2) % 3];
      if (sign < 0.0f) std::swap(du, dv);
      const glm::vec3 centre = c + n * h;
      const auto first = static_cast<uint32_t>(scene.positions.size());
      for (glm::vec2 corner :
           {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        scene.positions.push_back(centre + corner.x * du + corner.y * dv);
        scene.normals.push_back(n);
        scene.uvs.push_back(0.5f * (corner + 1.0f));
      }
      for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(first + i);
      scene.triangleMaterial.insert(scene.triangleMaterial.end(), 2, materialIndex);
    }
}

}  // namespace

Motion parseMotion(const std::string& word) {
  if (word == "static") return Motion::Static;
  if (word == "orbit") return Motion::Orbit;
  if (word == "sweep") return Motion::Sweep;
  if (word == "move") return Motion::Move;
  if (word == "path") return Motion::Path;
  throw engine::Error("--motion: '" + word + "' is not one of static, orbit, sweep, move, path");
}

uint32_t sweptLight(const engine::Scene& scene) {
  const int light = firstDirectedLight(scene);
  if (light < 0)
    throw engine::Error("--motion sweep: " + scene.source +
                        " has no spot or directional light to turn");
  return uint32_t(light);
}

Frame makeFrame(const engine::Scene& base, Motion motion, uint32_t t, uint32_t frames,
                uint32_t width, uint32_t height, const std::vector<PathFrame>* path) {
  Frame f{base, {}};
  const engine::Bounds b = base.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max), extent = b.max - b.min;
  const float s = phase(t, frames);
  engine::Camera camera = base.cameras.empty() ? engine::defaultCamera(base) : base.cameras.front();
  if (motion == Motion::Orbit)
    camera.cameraToWorld = aboutVertical(centre, kOrbitDegrees * s) * camera.cameraToWorld;
  if (motion == Motion::Sweep) {
    engine::Light& light = f.scene.lights.at(sweptLight(base));
    light.direction = glm::normalize(glm::vec3(aboutVertical(glm::vec3(0.0f), kSweepDegrees * s) *
                                               glm::vec4(light.direction, 0.0f)));
  }
  if (motion == Motion::Move) {
    const float side = 0.15f * std::min(extent.x, extent.z);
    addBox(f.scene, glm::vec3(centre.x + s * extent.x / 3.0f, b.min.y, centre.z),
           glm::vec3(side, side, side));
  }
  if (motion == Motion::Path) {
    assert(path && path->size() == frames);
    const PathFrame& recorded = path->at(t);
    camera = recorded.camera;
    f.scene.lights = recorded.lights;
  }
  f.view = engine::cameraView(camera, width, height);
  return f;
}

}  // namespace samples
