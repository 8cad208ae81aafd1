// The consumer test's scene: an open-topped 2 m room, a white floor and back wall, a red left
// and a green right wall, under a spot; its triangles in the module's std430 layouts, and a
// G-buffer ray-cast on the CPU, as a host's own rasteriser would have written it.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "shared/scene_data.h"

struct Room {
  std::vector<gpu::SceneVertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> triangleMaterials;
  std::vector<gpu::SceneMaterial> materials;
  glm::vec3 boundsMin{-1.0f, 0.0f, -1.0f}, boundsMax{1.0f, 2.0f, 1.0f};
  glm::mat4 view{1.0f}, proj{1.0f};  // the camera, Vulkan clip space
};
Room makeRoom(float aspect);

// The G-buffer's four images as bytes in their formats (R32F depth, RG16 SNORM octahedral
// normal, RGBA16F diffuse + roughness, RGBA16F F0 + F90), and each pixel's surface: the index of
// the quad it sees (floor 0, back 1, left 2, right 3) or -1 for the sky, and its position.
struct CpuGBuffer {
  std::vector<float> depth;
  std::vector<int16_t> normal;
  std::vector<uint16_t> diffuse, specular;
  std::vector<int> quad;
  std::vector<glm::vec3> position;
  std::vector<glm::vec3> worldNormal;  // facing the viewer; 0 for the sky
};
CpuGBuffer rayCastGBuffer(const Room& room, uint32_t width, uint32_t height);
