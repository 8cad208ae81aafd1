// A host outside the tree (issue 23): it finds the installed module with find_package(vsgl),
// creates its own Vulkan device, scene buffers and G-buffer (ray-cast on the CPU), records one
// frame of the module and checks what comes out: finite, non-negative light, none on the sky,
// light on almost every surface, and the floor next to the red wall redder than the floor next
// to the green one. Under the validation layer when it is installed: a message fails the run.
#include <cmath>
#include <cstdio>
#include <exception>

#include "indirect.h"
#include "room.h"
#include "vulkan_host.h"

int main() try {
  const uint32_t width = 96, height = 64;
  VulkanHost host;
  const Room room = makeRoom(float(width) / float(height));
  const CpuGBuffer cpu = rayCastGBuffer(room, width, height);

  HostScene scene;
  gi::SceneGeometry& g = scene.geometry;
  const HostBuffer vertices = host.buffer(room.vertices.data(), room.vertices.size() * sizeof(gpu::SceneVertex));
  const HostBuffer indices = host.buffer(room.indices.data(), room.indices.size() * 4);
  const HostBuffer triangleMaterials = host.buffer(room.triangleMaterials.data(), room.triangleMaterials.size() * 4);
  const HostBuffer materials = host.buffer(room.materials.data(), room.materials.size() * sizeof(gpu::SceneMaterial));
  g.vertices = vertices.buffer, g.vertexBytes = vertices.size;
  g.indices = indices.buffer, g.indexBytes = indices.size;
  g.triangleMaterials = triangleMaterials.buffer, g.triangleMaterialBytes = triangleMaterials.size;
  g.materials = materials.buffer, g.materialBytes = materials.size;
  g.triangleCount = static_cast<uint32_t>(room.indices.size() / 3);
  g.vertexCount = static_cast<uint32_t>(room.vertices.size());
  g.materialCount = static_cast<uint32_t>(room.materials.size());
  g.indexData = room.indices, g.triangleMaterialData = room.triangleMaterials;
  // No textures: one white texel each (the materials name no layer).
  const uint8_t white[4] = {255, 255, 255, 255};
  const HostImage colour = host.image(VK_FORMAT_R8G8B8A8_SRGB, 1, 1, VK_IMAGE_USAGE_SAMPLED_BIT, 1, true);
  const HostImage data = host.image(VK_FORMAT_R8G8B8A8_UNORM, 1, 1, VK_IMAGE_USAGE_SAMPLED_BIT, 1, true);
  host.upload(colour, white, 4, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  host.upload(data, white, 4, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  g.baseColorTextures = colour.view, g.dataTextures = data.view, g.sampler = host.sampler();
  g.boundsMin = room.boundsMin, g.boundsMax = room.boundsMax;
  g.alphaCutouts = false;

  const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
  const VkImageLayout readOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const HostImage depth = host.image(VK_FORMAT_R32_SFLOAT, width, height, storage | VK_IMAGE_USAGE_SAMPLED_BIT);
  const HostImage normal = host.image(VK_FORMAT_R16G16_SNORM, width, height, storage | VK_IMAGE_USAGE_SAMPLED_BIT);
  const HostImage diffuse = host.image(VK_FORMAT_R16G16B16A16_SFLOAT, width, height, storage | VK_IMAGE_USAGE_SAMPLED_BIT);
  const HostImage specular = host.image(VK_FORMAT_R16G16B16A16_SFLOAT, width, height, storage | VK_IMAGE_USAGE_SAMPLED_BIT);
  host.upload(depth, cpu.depth.data(), cpu.depth.size() * 4, readOnly);
  host.upload(normal, cpu.normal.data(), cpu.normal.size() * 2, readOnly);
  host.upload(diffuse, cpu.diffuse.data(), cpu.diffuse.size() * 2, readOnly);
  host.upload(specular, cpu.specular.data(), cpu.specular.size() * 2, readOnly);
  scene.gbuffer = {width, height, {depth.image, depth.view, readOnly}, {normal.image, normal.view, readOnly},
                   {diffuse.image, diffuse.view, readOnly}, {specular.image, specular.view, readOnly}};
  scene.camera = {room.view, room.proj};
  scene.light.type = gi::Light::Type::Spot;
  scene.light.position = {0.0f, 1.9f, 0.2f};
  scene.light.direction = {0.0f, -1.0f, 0.0f};
  scene.light.intensity = 10.0f;
  scene.light.innerConeAngle = 0.5f;
  scene.light.outerConeAngle = 0.7f;

  std::unique_ptr<gi::IndirectLighting> module;
  gi::FrameOutput out;
  std::string error;
  host.submit([&](VkCommandBuffer cmd) {
    module = recordIndirect({host.instance, host.physicalDevice, host.device, host.queueFamily}, scene, cmd,
                            &out, &error);
  });
  if (!module) {
    std::fprintf(stderr, "consumer: %s\n", error.c_str());
    return 1;
  }
  HostImage result;
  result.image = out.indirectDiffuse.image;
  result.width = width;
  result.height = height;
  const std::vector<float> light = host.readRgba32f(result, out.indirectDiffuse.layout);

  size_t surface = 0, lit = 0, bad = 0, litSky = 0;
  glm::dvec3 nearRed(0.0), nearGreen(0.0);
  for (size_t i = 0; i < size_t{width} * height; ++i) {
    const glm::vec3 c(light[4 * i], light[4 * i + 1], light[4 * i + 2]);
    if (!std::isfinite(c.r + c.g + c.b) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) ++bad;
    if (cpu.quad[i] < 0) {
      litSky += c != glm::vec3(0.0f);
      continue;
    }
    ++surface;
    lit += c.r + c.g + c.b > 0.0f;
    if (cpu.quad[i] == 0 && cpu.position[i].x < -0.5f) nearRed += glm::dvec3(c);
    if (cpu.quad[i] == 0 && cpu.position[i].x > 0.5f) nearGreen += glm::dvec3(c);
  }
  const double redTint = nearRed.r / nearRed.g, greenTint = nearGreen.r / nearGreen.g;
  std::printf("consumer: %zu of %zu surface pixels lit, %zu bad, %zu sky pixels lit; floor r/g "
              "%.2f by the red wall, %.2f by the green; %u validation messages\n",
              lit, surface, bad, litSky, redTint, greenTint, host.validationMessages);
  module.reset();
  const bool ok = bad == 0 && litSky == 0 && lit * 10 >= surface * 9 && redTint > 1.2 * greenTint &&
                  host.validationMessages == 0;
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "consumer: %s\n", e.what());
  return 1;
}
