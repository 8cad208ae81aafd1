#include "sphere_gbuffer.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/packing.hpp>
#include <vector>

#include "engine/commands.h"
#include "engine/gbuffer_reference.h"

namespace testing_gpu {

namespace {

uint16_t snorm16(double v) {
  return static_cast<uint16_t>(
      static_cast<int16_t>(std::lround(std::clamp(v, -1.0, 1.0) * 32767.0)));
}

// Octahedral encoding (common/octahedral.glsl) in double.
glm::dvec2 octEncode(glm::dvec3 n) {
  const glm::dvec2 p = glm::dvec2(n.x, n.y) / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
  if (n.z > 0.0) return p;
  const glm::dvec2 sign(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
  return (1.0 - glm::abs(glm::dvec2(p.y, p.x))) * sign;
}

}  // namespace

engine::View sphereView(uint32_t width, uint32_t height) {
  const glm::vec3 eye(0.0f, 1.2f, 3.0f);
  return engine::makeView(engine::lookAlong(eye, -eye, {0.0f, 1.0f, 0.0f}),
                          engine::perspectiveVulkan(0.75f, 1.0f, 0.1f, 100.0f), width, height);
}

engine::GBuffer sphereGBuffer(engine::Context& ctx, const engine::View& view,
                              const SphereMaterialFunction& material) {
  const uint32_t width = view.width, height = view.height;
  engine::GBuffer gbuffer = engine::createGBuffer(ctx, width, height);
  const size_t count = size_t{width} * height;
  std::vector<float> depth(count, 1.0f);
  std::vector<uint16_t> normal(2 * count, 0), diffuse(4 * count, 0), specular(4 * count, 0);
  const glm::dmat4 viewProj(view.viewProj);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t i = size_t{y} * width + x;
      const engine::CameraRay ray = engine::cameraRayReference(view, glm::dvec2(x, y) + 0.5);
      const double b = glm::dot(ray.origin, ray.dir);
      const double disc = b * b - (glm::dot(ray.origin, ray.origin) - 1.0);
      if (disc <= 0.0) continue;
      const glm::dvec3 p = ray.origin + (-b - std::sqrt(disc)) * ray.dir;
      const glm::dvec4 clip = viewProj * glm::dvec4(p, 1.0);
      depth[i] = static_cast<float>(clip.z / clip.w);
      const glm::dvec2 e = octEncode(glm::normalize(p));
      normal[2 * i] = snorm16(e.x);
      normal[2 * i + 1] = snorm16(e.y);
      const SphereMaterial m = material(x, y);
      for (int c = 0; c < 3; ++c) {
        diffuse[4 * i + c] = glm::packHalf1x16(static_cast<float>(m.albedo[c]));
        specular[4 * i + c] = glm::packHalf1x16(static_cast<float>(m.f0[c]));
      }
      diffuse[4 * i + 3] = glm::packHalf1x16(static_cast<float>(m.roughness));
      specular[4 * i + 3] = glm::packHalf1x16(static_cast<float>(m.f90));
    }
  gbuffer.depth.upload(ctx, depth.data(), depth.size() * sizeof(float));
  gbuffer.normal.upload(ctx, normal.data(), normal.size() * sizeof(uint16_t));
  gbuffer.diffuse.upload(ctx, diffuse.data(), diffuse.size() * sizeof(uint16_t));
  gbuffer.specular.upload(ctx, specular.data(), specular.size() * sizeof(uint16_t));
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    for (engine::Image* image :
         {&gbuffer.depth, &gbuffer.normal, &gbuffer.diffuse, &gbuffer.specular})
      engine::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_GENERAL);
  });
  return gbuffer;
}

}  // namespace testing_gpu
