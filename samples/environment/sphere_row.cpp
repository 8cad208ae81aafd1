#include "sphere_row.h"

#include <cmath>
#include <glm/glm.hpp>
#include <numbers>

namespace environment {
namespace {

struct SphereMaterial {
  const char* name;
  glm::vec3 baseColor;  // linear; a metal's F0, a dielectric's albedo (F0 0.04)
  float roughness;      // perceptual; GGX alpha = r^2
  float metallic;
};

// Left to right: roughness 0.1 .. 0.8, metals and dielectrics alternating.
constexpr SphereMaterial kMaterials[kSphereCount] = {
    {"gold r=0.1", {1.00f, 0.78f, 0.34f}, 0.10f, 1.0f},
    {"red plastic r=0.25", {0.60f, 0.08f, 0.06f}, 0.25f, 0.0f},
    {"silver r=0.4", {0.95f, 0.93f, 0.88f}, 0.40f, 1.0f},
    {"blue plastic r=0.6", {0.08f, 0.20f, 0.60f}, 0.60f, 0.0f},
    {"copper r=0.8", {0.95f, 0.64f, 0.54f}, 0.80f, 1.0f},
};

void addSphere(engine::Scene& scene, glm::vec3 centre, uint32_t material) {
  const auto base = static_cast<uint32_t>(scene.positions.size());
  constexpr double kPi = std::numbers::pi;
  for (int ring = 0; ring <= kSphereRings; ++ring) {
    const double theta = kPi * ring / kSphereRings;  // from +y
    for (int segment = 0; segment <= kSphereSegments; ++segment) {
      const double phi = 2.0 * kPi * segment / kSphereSegments;
      const glm::vec3 n(static_cast<float>(std::sin(theta) * std::cos(phi)),
                        static_cast<float>(std::cos(theta)),
                        static_cast<float>(-std::sin(theta) * std::sin(phi)));
      scene.positions.push_back(centre + kSphereRadius * n);
      scene.normals.push_back(n);
      scene.uvs.emplace_back(float(segment) / kSphereSegments, float(ring) / kSphereRings);
    }
  }
  // Counter-clockwise seen from outside: ring r to r + 1 goes down, segment s to s + 1 goes
  // eastward (phi turns from +x towards -z), so (r, s), (r + 1, s), (r + 1, s + 1) winds
  // anticlockwise around the outward normal. Degenerate triangles at the poles are skipped.
  const uint32_t row = kSphereSegments + 1;
  for (uint32_t ring = 0; ring < uint32_t(kSphereRings); ++ring)
    for (uint32_t segment = 0; segment < uint32_t(kSphereSegments); ++segment) {
      const uint32_t a = base + ring * row + segment, b = a + row, c = b + 1, d = a + 1;
      if (ring != 0) {
        scene.indices.insert(scene.indices.end(), {a, b, d});
        scene.triangleMaterial.push_back(material);
      }
      if (ring + 1 != uint32_t(kSphereRings)) {
        scene.indices.insert(scene.indices.end(), {d, b, c});
        scene.triangleMaterial.push_back(material);
      }
    }
}

}  // namespace

engine::Scene makeSphereRow(float aspect) {
  engine::Scene scene;
  scene.source = "builtin:sphere-row";
  for (int i = 0; i < kSphereCount; ++i) {
    engine::Material m;
    m.name = kMaterials[i].name;
    m.baseColorFactor = glm::vec4(kMaterials[i].baseColor, 1.0f);
    m.roughnessFactor = kMaterials[i].roughness;
    m.metallicFactor = kMaterials[i].metallic;
    scene.materials.push_back(m);
    const float x = (float(i) - 0.5f * float(kSphereCount - 1)) * kSphereSpacing;
    addSphere(scene, {x, 0.0f, 0.0f}, uint32_t(i));
  }
  // A camera slightly above the row's plane, far enough for little perspective: the row's half
  // width plus a margin must fit the horizontal field of view, the spheres' height the vertical.
  const glm::vec3 eye(0.0f, 0.35f, 7.0f), target(0.0f);
  const float distance = glm::length(target - eye);
  const float halfWidth = 0.5f * float(kSphereCount - 1) * kSphereSpacing + kSphereRadius + 0.2f;
  const float halfHeight = kSphereRadius + 0.15f;
  const float tanHalf = std::max(halfWidth / distance / aspect, halfHeight / distance);
  const glm::vec3 forward = glm::normalize(target - eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::cross(right, forward);
  engine::Camera camera;
  camera.name = "camera";
  camera.cameraToWorld = glm::mat4(glm::vec4(right, 0.0f), glm::vec4(up, 0.0f),
                                   glm::vec4(-forward, 0.0f), glm::vec4(eye, 1.0f));
  camera.yfov = 2.0f * std::atan(tanHalf);
  camera.znear = 1.0f;
  camera.zfar = 20.0f;
  scene.cameras = {camera};
  return scene;
}

std::string sphereRowDescription() {
  std::string out;
  for (const SphereMaterial& m : kMaterials) out += (out.empty() ? "" : ", ") + std::string(m.name);
  return out;
}

}  // namespace environment
