// A host outside the tree (issue 23): it finds the installed module with find_package(vsgl),
// creates its own Vulkan device, scene buffers and G-buffer (ray-cast on the CPU), records one
// frame of the module and checks what comes out: finite, non-negative light, none on the sky,
// light on almost every surface, and the floor next to the red wall redder than the floor next
// to the green one. Under the validation layer when it is installed: a message fails the run.
#include <cmath>
#include <cstdio>
#include <exception>
#include <glm/gtc/packing.hpp>

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

  // The same frame from a G-buffer as many renderers keep it: reversed-Z depth in a D32 depth
  // image (with the reversed projection) and world-space normals in RGBA16F. The module converts
  // both; the light must agree with the first frame's to 0.1 % of its mean (the conversions round
  // in fp32, the half normals to 2^-11: docs/integration.md).
  std::vector<float> reversed(cpu.depth.size());
  std::vector<uint16_t> worldNormals(4 * cpu.depth.size(), 0);
  for (size_t i = 0; i < cpu.depth.size(); ++i) {
    reversed[i] = 1.0f - cpu.depth[i];
    for (int c = 0; c < 3; ++c) worldNormals[4 * i + c] = glm::packHalf1x16(cpu.worldNormal[i][c]);
  }
  const HostImage depth32 = host.image(VK_FORMAT_D32_SFLOAT, width, height, VK_IMAGE_USAGE_SAMPLED_BIT);
  const HostImage rgbNormal = host.image(VK_FORMAT_R16G16B16A16_SFLOAT, width, height, VK_IMAGE_USAGE_SAMPLED_BIT);
  host.upload(depth32, reversed.data(), reversed.size() * 4, readOnly);
  host.upload(rgbNormal, worldNormals.data(), worldNormals.size() * 2, readOnly);
  // The first frame left the G-buffer in the layout it reports.
  for (gi::ImageRef* image : {&scene.gbuffer.depth, &scene.gbuffer.normal, &scene.gbuffer.diffuse,
                              &scene.gbuffer.specular})
    image->layout = out.gbufferLayout;
  HostScene encoded = scene;
  encoded.gbuffer.depth = {depth32.image, depth32.view, readOnly};
  encoded.gbuffer.normal = {rgbNormal.image, rgbNormal.view, readOnly};
  encoded.gbuffer.depthEncoding = gi::DepthEncoding::ReversedNdc;
  encoded.gbuffer.depthFormat = VK_FORMAT_D32_SFLOAT;
  encoded.gbuffer.normalEncoding = gi::NormalEncoding::WorldSigned;
  glm::mat4 flip(1.0f);  // clip z -> w - z
  flip[2][2] = -1.0f;
  flip[3][2] = 1.0f;
  encoded.camera.proj = flip * room.proj;
  std::unique_ptr<gi::IndirectLighting> second;
  gi::FrameOutput out2;
  host.submit([&](VkCommandBuffer cmd) {
    second = recordIndirect({host.instance, host.physicalDevice, host.device, host.queueFamily},
                            encoded, cmd, &out2, &error);
  });
  if (!second) {
    std::fprintf(stderr, "consumer: %s\n", error.c_str());
    return 1;
  }
  result.image = out2.indirectDiffuse.image;
  const std::vector<float> light2 = host.readRgba32f(result, out2.indirectDiffuse.layout);
  double sum = 0.0, sum2 = 0.0;
  for (size_t i = 0; i < light.size(); ++i)
    if (i % 4 != 3) {
      sum += light[i];
      sum2 += light2[i];
    }
  const double encodedRatio = sum2 / sum;

  std::printf("consumer: %zu of %zu surface pixels lit, %zu bad, %zu sky pixels lit; floor r/g "
              "%.2f by the red wall, %.2f by the green; D32 reversed-Z and RGBA16F normals: %.5f "
              "of the light; %u validation messages\n",
              lit, surface, bad, litSky, redTint, greenTint, encodedRatio,
              host.validationMessages);
  module.reset();
  second.reset();
  const bool ok = bad == 0 && litSky == 0 && lit * 10 >= surface * 9 && redTint > 1.2 * greenTint &&
                  std::abs(encodedRatio - 1.0) <= 1e-3 && host.validationMessages == 0;
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "consumer: %s\n", e.what());
  return 1;
}
