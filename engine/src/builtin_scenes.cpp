#include "engine/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <utility>

#include "engine/error.h"

namespace engine {
namespace {

// Builds a Scene from tessellated rectangles and boxes.
class ProceduralScene {
 public:
  explicit ProceduralScene(const std::string& name) { scene_.source = "builtin:" + name; }
  // More geometry, materials and lights added to `base`.
  ProceduralScene(Scene base, const std::string& name) : scene_(std::move(base)) {
    scene_.source = "builtin:" + name;
  }

  uint32_t addMaterial(const std::string& name, glm::vec3 baseColor, float roughness,
                       float metallic) {
    Material material;
    material.name = name;
    material.baseColorFactor = glm::vec4(baseColor, 1.0f);
    material.roughnessFactor = roughness;
    material.metallicFactor = metallic;
    scene_.materials.push_back(std::move(material));
    return static_cast<uint32_t>(scene_.materials.size() - 1);
  }

  // The parallelogram corner + s * edgeU + t * edgeV, s, t in [0, 1], cut into a grid of cells
  // no longer than maxCell along either edge. Its front (counter-clockwise) side is the one
  // cross(edgeU, edgeV) points to. UVs run over [0, 1] along the two edges.
  void addRect(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, uint32_t material,
               float maxCell) {
    const int cellsU = std::max(1, static_cast<int>(std::ceil(glm::length(edgeU) / maxCell)));
    const int cellsV = std::max(1, static_cast<int>(std::ceil(glm::length(edgeV) / maxCell)));
    const glm::vec3 normal = glm::normalize(glm::cross(edgeU, edgeV));
    const auto base = static_cast<uint32_t>(scene_.positions.size());
    for (int j = 0; j <= cellsV; ++j) {
      for (int i = 0; i <= cellsU; ++i) {
        const float s = static_cast<float>(i) / static_cast<float>(cellsU);
        const float t = static_cast<float>(j) / static_cast<float>(cellsV);
        scene_.positions.push_back(corner + s * edgeU + t * edgeV);
        scene_.normals.push_back(normal);
        scene_.uvs.emplace_back(s, t);
      }
    }
    const auto rowLength = static_cast<uint32_t>(cellsU + 1);
    for (uint32_t j = 0; j < static_cast<uint32_t>(cellsV); ++j) {
      for (uint32_t i = 0; i < static_cast<uint32_t>(cellsU); ++i) {
        const uint32_t v00 = base + j * rowLength + i;
        const uint32_t v10 = v00 + 1;
        const uint32_t v01 = v00 + rowLength;
        const uint32_t v11 = v01 + 1;
        scene_.indices.insert(scene_.indices.end(), {v00, v10, v11, v00, v11, v01});
        scene_.triangleMaterial.insert(scene_.triangleMaterial.end(), 2, material);
      }
    }
  }

  // A box standing on y = baseCentre.y, turned by yaw radians about +Y, faces pointing out.
  // No bottom face: every box stands on a floor, where it could never be seen or lit.
  void addBox(glm::vec3 baseCentre, glm::vec3 size, float yaw, uint32_t material, float maxCell) {
    const glm::vec3 ax(std::cos(yaw), 0.0f, -std::sin(yaw));
    const glm::vec3 ay(0.0f, 1.0f, 0.0f);
    const glm::vec3 az(std::sin(yaw), 0.0f, std::cos(yaw));
    const glm::vec3 hx = 0.5f * size.x * ax;
    const glm::vec3 hz = 0.5f * size.z * az;
    const glm::vec3 up = size.y * ay;
    const glm::vec3 c = baseCentre;
    addRect(c + hx + hz, -2.0f * hz, up, material, maxCell);              // +X side
    addRect(c - hx - hz, 2.0f * hz, up, material, maxCell);               // -X side
    addRect(c - hx + hz, 2.0f * hx, up, material, maxCell);               // +Z side
    addRect(c + hx - hz, -2.0f * hx, up, material, maxCell);              // -Z side
    addRect(c + up - hx + hz, 2.0f * hx, -2.0f * hz, material, maxCell);  // top
  }

  // A UV sphere of about `triangles` triangles (at least 8 stacks by 16 slices), faces out.
  void addSphere(glm::vec3 centre, float radius, uint32_t triangles, uint32_t material) {
    // slices = 2 stacks: 2 slices (stacks - 1) = 4 stacks^2 - 4 stacks triangles.
    const auto stacks = std::max(
        8u, static_cast<uint32_t>(std::lround(0.5 + std::sqrt(0.25 + double(triangles) / 4.0))));
    const uint32_t slices = 2 * stacks;
    const auto base = static_cast<uint32_t>(scene_.positions.size());
    for (uint32_t j = 0; j <= stacks; ++j) {
      const float theta = std::numbers::pi_v<float> * float(j) / float(stacks);
      for (uint32_t i = 0; i <= slices; ++i) {
        const float phi = 2.0f * std::numbers::pi_v<float> * float(i) / float(slices);
        const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                          -std::sin(theta) * std::sin(phi));
        scene_.positions.push_back(centre + radius * n);
        scene_.normals.push_back(n);
        scene_.uvs.emplace_back(float(i) / float(slices), float(j) / float(stacks));
      }
    }
    for (uint32_t j = 0; j < stacks; ++j)
      for (uint32_t i = 0; i < slices; ++i) {
        const uint32_t v00 = base + j * (slices + 1) + i, v10 = v00 + 1;
        const uint32_t v01 = v00 + slices + 1, v11 = v01 + 1;
        // The poles' rows have one triangle per cell, the others two.
        if (j > 0) {
          scene_.indices.insert(scene_.indices.end(), {v00, v01, v10});
          scene_.triangleMaterial.push_back(material);
        }
        if (j + 1 < stacks) {
          scene_.indices.insert(scene_.indices.end(), {v10, v01, v11});
          scene_.triangleMaterial.push_back(material);
        }
      }
  }

  void addSpotLight(const std::string& name, glm::vec3 position, glm::vec3 target, float intensity,
                    float innerCone, float outerCone, glm::vec3 color = glm::vec3(1.0f)) {
    Light light;
    light.name = name;
    light.type = LightType::Spot;
    light.position = position;
    light.direction = glm::normalize(target - position);
    light.color = color;
    light.intensity = intensity;
    light.innerConeAngle = innerCone;
    light.outerConeAngle = outerCone;
    scene_.lights.push_back(std::move(light));
  }

  void addPointLight(const std::string& name, glm::vec3 position, glm::vec3 color,
                     float intensity) {
    Light light;
    light.name = name;
    light.type = LightType::Point;
    light.position = position;
    light.color = color;
    light.intensity = intensity;
    scene_.lights.push_back(std::move(light));
  }

  void addSun(const std::string& name, glm::vec3 direction, float illuminance) {
    Light light;
    light.name = name;
    light.type = LightType::Directional;
    light.direction = glm::normalize(direction);
    light.intensity = illuminance;
    scene_.lights.push_back(std::move(light));
  }

  void setCamera(glm::vec3 eye, glm::vec3 target, float yfov) {
    // Camera looks down its local -Z with +Y up (glTF), so the columns are right, up, -forward.
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    Camera camera;
    camera.name = "camera";
    camera.cameraToWorld = glm::mat4(glm::vec4(right, 0.0f), glm::vec4(up, 0.0f),
                                     glm::vec4(-forward, 0.0f), glm::vec4(eye, 1.0f));
    camera.yfov = yfov;
    scene_.cameras = {camera};
  }

  Scene take() { return std::move(scene_); }

 private:
  Scene scene_;
};

// Cornell-style box, widened for 16:9 images: x in [-1.6, 1.6], y in [0, 2], z in [-1, 1], open
// towards +Z.
Scene makeCornell() {
  constexpr float kHalfWidth = 1.6f;  // half the room width (x), metres
  constexpr float kHalf = 1.0f;       // half the room depth (z), metres
  constexpr float kHeight = 2.0f;
  constexpr float kWallCell = 0.2f;  // 10 x 10 cells per wall
  constexpr float kBoxCell = 0.15f;
  // Albedos of the classic Cornell box measurements, roughly, in linear RGB.
  constexpr glm::vec3 kWhite(0.73f, 0.73f, 0.73f);
  constexpr glm::vec3 kRed(0.63f, 0.065f, 0.05f);
  constexpr glm::vec3 kGreen(0.14f, 0.45f, 0.091f);
  constexpr glm::vec3 kFloorGrey(0.5f, 0.5f, 0.52f);
  constexpr float kDiffuseRoughness = 0.9f;
  constexpr float kGlossyWallRoughness = 0.25f;  // glossy dielectric: a blurred reflection
  constexpr float kGlossyFloorRoughness = 0.2f;  // polished floor, reflects the boxes
  // Spot near the ceiling, above the front of the room, aimed down at the floor just in front
  // of the back wall: it lights the floor, the lower walls and both boxes; ceiling and upper
  // walls only receive bounce light. 20 W/sr gives ~5 W/m^2 on the floor 2 m away.
  constexpr glm::vec3 kSpotPosition(0.0f, 1.9f, 0.6f);
  constexpr glm::vec3 kSpotTarget(0.0f, 0.0f, -0.6f);
  constexpr float kSpotIntensity = 20.0f;  // W/sr
  constexpr float kSpotInner = 0.45f;      // radians
  constexpr float kSpotOuter = 0.6f;       // radians
  // The camera sits outside the open face; with this yfov the opening fills the frame
  // vertically, and the widened room fills it horizontally up to a 16:9 aspect, so the view
  // never leaves the box.
  constexpr glm::vec3 kEye(0.0f, 1.0f, 3.4f);
  constexpr glm::vec3 kLookAt(0.0f, 1.0f, 0.0f);
  constexpr float kYfov = 0.69f;

  ProceduralScene s("cornell");
  const uint32_t white = s.addMaterial("white", kWhite, kDiffuseRoughness, 0.0f);
  const uint32_t red = s.addMaterial("red", kRed, kDiffuseRoughness, 0.0f);
  const uint32_t green = s.addMaterial("glossy green", kGreen, kGlossyWallRoughness, 0.0f);
  const uint32_t floor = s.addMaterial("glossy floor", kFloorGrey, kGlossyFloorRoughness, 0.0f);

  const float w = 2.0f * kHalfWidth, d = 2.0f * kHalf;
  s.addRect({-kHalfWidth, 0.0f, kHalf}, {w, 0.0f, 0.0f}, {0.0f, 0.0f, -d}, floor, kWallCell);
  s.addRect({-kHalfWidth, kHeight, -kHalf}, {w, 0.0f, 0.0f}, {0.0f, 0.0f, d}, white, kWallCell);
  s.addRect({-kHalfWidth, 0.0f, -kHalf}, {w, 0.0f, 0.0f}, {0.0f, kHeight, 0.0f}, white, kWallCell);
  s.addRect({-kHalfWidth, 0.0f, kHalf}, {0.0f, 0.0f, -d}, {0.0f, kHeight, 0.0f}, red, kWallCell);
  s.addRect({kHalfWidth, 0.0f, -kHalf}, {0.0f, 0.0f, d}, {0.0f, kHeight, 0.0f}, green, kWallCell);
  s.addBox({-0.35f, 0.0f, -0.35f}, {0.6f, 1.2f, 0.6f}, 0.3f, white, kBoxCell);  // tall
  s.addBox({0.4f, 0.0f, 0.3f}, {0.6f, 0.6f, 0.6f}, -0.3f, white, kBoxCell);     // short

  s.addSpotLight("ceiling spot", kSpotPosition, kSpotTarget, kSpotIntensity, kSpotInner,
                 kSpotOuter);
  s.setCamera(kEye, kLookAt, kYfov);
  return s.take();
}

// Hall: floor x, z in [-4, 4], walls at x = +-4 and z = -4 up to a 0.2 m ceiling slab at y = 3
// with a 2 x 4 m skylight; open towards +Z behind the camera.
Scene makeAtrium() {
  constexpr float kHalf = 4.0f;
  constexpr float kHeight = 3.0f;
  constexpr float kSlabThickness = 0.2f;
  constexpr float kCell = 0.4f;
  constexpr float kColumnCell = 0.25f;
  constexpr float kSkylightMinX = -1.0f;
  constexpr float kSkylightMaxX = 1.0f;
  constexpr float kSkylightMinZ = -3.0f;
  constexpr float kSkylightMaxZ = 1.0f;
  constexpr float kColumnWidth = 0.4f;
  constexpr float kColumnRowX = 1.5f;  // two rows at x = +-1.5, either side of the skylight
  constexpr float kColumnZ[] = {-2.5f, -1.0f, 0.5f, 2.0f};
  constexpr glm::vec3 kStone(0.55f, 0.5f, 0.45f);
  constexpr glm::vec3 kPlaster(0.8f, 0.78f, 0.75f);
  constexpr glm::vec3 kConcrete(0.6f, 0.6f, 0.6f);
  // Sun 53 degrees above the horizon. Through the skylight it lands on the floor around the
  // right column row (1.7 m to +X, 1.5 m to -Z of the opening), so the columns cast shadows and
  // most of the hall is lit only indirectly. 3 W/m^2 on a plane facing the sun: far below the
  // real sun, chosen so the sunlit patch is exposed like the spot-lit scenes.
  constexpr glm::vec3 kSunDirection(0.45f, -0.8f, -0.4f);
  constexpr float kSunIlluminance = 3.0f;
  constexpr glm::vec3 kEye(0.0f, 1.6f, 3.6f);
  constexpr glm::vec3 kLookAt(0.0f, 1.2f, -4.0f);
  constexpr float kYfov = 1.0f;

  ProceduralScene s("atrium");
  const uint32_t stone = s.addMaterial("stone floor", kStone, 0.6f, 0.0f);
  const uint32_t plaster = s.addMaterial("plaster", kPlaster, 0.95f, 0.0f);
  const uint32_t concrete = s.addMaterial("concrete", kConcrete, 0.5f, 0.0f);

  const float w = 2.0f * kHalf;
  s.addRect({-kHalf, 0.0f, kHalf}, {w, 0.0f, 0.0f}, {0.0f, 0.0f, -w}, stone, kCell);
  s.addRect({-kHalf, 0.0f, -kHalf}, {w, 0.0f, 0.0f}, {0.0f, kHeight, 0.0f}, plaster, kCell);
  s.addRect({-kHalf, 0.0f, kHalf}, {0.0f, 0.0f, -w}, {0.0f, kHeight, 0.0f}, plaster, kCell);
  s.addRect({kHalf, 0.0f, -kHalf}, {0.0f, 0.0f, w}, {0.0f, kHeight, 0.0f}, plaster, kCell);

  // Slab: four pieces around the skylight, each with an underside (facing down into the hall)
  // and a top (facing the sky, so the slab casts the sun's shadow from either side).
  struct Piece {
    float minX, maxX, minZ, maxZ;
  };
  const Piece pieces[] = {{-kHalf, kHalf, kSkylightMaxZ, kHalf},
                          {-kHalf, kHalf, -kHalf, kSkylightMinZ},
                          {-kHalf, kSkylightMinX, kSkylightMinZ, kSkylightMaxZ},
                          {kSkylightMaxX, kHalf, kSkylightMinZ, kSkylightMaxZ}};
  const float top = kHeight + kSlabThickness;
  for (const Piece& p : pieces) {
    const float dx = p.maxX - p.minX;
    const float dz = p.maxZ - p.minZ;
    s.addRect({p.minX, kHeight, p.minZ}, {dx, 0.0f, 0.0f}, {0.0f, 0.0f, dz}, concrete, kCell);
    s.addRect({p.minX, top, p.maxZ}, {dx, 0.0f, 0.0f}, {0.0f, 0.0f, -dz}, concrete, kCell);
  }
  // The skylight's reveals, facing into the opening.
  const glm::vec3 thickness(0.0f, kSlabThickness, 0.0f);
  const float sx = kSkylightMaxX - kSkylightMinX;
  const float sz = kSkylightMaxZ - kSkylightMinZ;
  s.addRect({kSkylightMinX, kHeight, kSkylightMinZ}, {sx, 0.0f, 0.0f}, thickness, concrete, kCell);
  s.addRect({kSkylightMaxX, kHeight, kSkylightMaxZ}, {-sx, 0.0f, 0.0f}, thickness, concrete, kCell);
  s.addRect({kSkylightMinX, kHeight, kSkylightMaxZ}, {0.0f, 0.0f, -sz}, thickness, concrete, kCell);
  s.addRect({kSkylightMaxX, kHeight, kSkylightMinZ}, {0.0f, 0.0f, sz}, thickness, concrete, kCell);

  for (float x : {-kColumnRowX, kColumnRowX}) {
    for (float z : kColumnZ) {
      s.addBox({x, 0.0f, z}, {kColumnWidth, kHeight, kColumnWidth}, 0.0f, concrete, kColumnCell);
    }
  }

  s.addSun("sun", kSunDirection, kSunIlluminance);
  s.setCamera(kEye, kLookAt, kYfov);
  return s.take();
}

// Checker floor x, z in [-1.2, 1.2] with a back wall at z = -1.2 and a side wall at x = -1.2.
Scene makeChecker() {
  constexpr float kHalf = 1.2f;
  constexpr int kTiles = 24;  // per side: 0.1 m tiles
  constexpr float kWallHeight = 1.6f;
  constexpr float kWallCell = 0.2f;
  // Black polished stone against matte white: the glossy lobe (GGX alpha = 0.08^2) flips the
  // reflected radiance tile by tile, the hardest case for a smooth sampling distribution.
  constexpr glm::vec3 kGlossyTile(0.05f, 0.05f, 0.05f);
  constexpr float kGlossyRoughness = 0.08f;
  constexpr glm::vec3 kRoughTile(0.8f, 0.8f, 0.8f);
  constexpr float kRoughRoughness = 0.9f;
  constexpr glm::vec3 kBackWall(0.75f, 0.75f, 0.72f);
  constexpr glm::vec3 kSideWall(0.2f, 0.3f, 0.7f);
  // Spot 22 degrees above the floor at the front right, aimed across the floor towards the
  // back-left corner: the floor is lit at a grazing angle and the walls catch the bounce.
  constexpr glm::vec3 kSpotPosition(0.9f, 0.8f, 1.1f);
  constexpr glm::vec3 kSpotTarget(-0.2f, 0.0f, -0.5f);
  constexpr float kSpotIntensity = 12.0f;  // W/sr: ~2.7 W/m^2 normal to the beam at 2.1 m
  constexpr float kSpotInner = 0.35f;
  constexpr float kSpotOuter = 0.5f;
  constexpr glm::vec3 kEye(0.3f, 1.0f, 2.1f);
  constexpr glm::vec3 kLookAt(-0.15f, 0.2f, -0.4f);
  constexpr float kYfov = 0.75f;

  ProceduralScene s("checker");
  const uint32_t glossy = s.addMaterial("glossy tile", kGlossyTile, kGlossyRoughness, 0.0f);
  const uint32_t rough = s.addMaterial("rough tile", kRoughTile, kRoughRoughness, 0.0f);
  const uint32_t back = s.addMaterial("back wall", kBackWall, kRoughRoughness, 0.0f);
  const uint32_t side = s.addMaterial("side wall", kSideWall, kRoughRoughness, 0.0f);

  const float tile = 2.0f * kHalf / static_cast<float>(kTiles);
  for (int j = 0; j < kTiles; ++j) {
    for (int i = 0; i < kTiles; ++i) {
      const glm::vec3 corner(-kHalf + static_cast<float>(i) * tile, 0.0f,
                             kHalf - static_cast<float>(j) * tile);
      s.addRect(corner, {tile, 0.0f, 0.0f}, {0.0f, 0.0f, -tile}, (i + j) % 2 == 0 ? glossy : rough,
                tile);
    }
  }
  const float w = 2.0f * kHalf;
  s.addRect({-kHalf, 0.0f, -kHalf}, {w, 0.0f, 0.0f}, {0.0f, kWallHeight, 0.0f}, back, kWallCell);
  s.addRect({-kHalf, 0.0f, kHalf}, {0.0f, 0.0f, -w}, {0.0f, kWallHeight, 0.0f}, side, kWallCell);

  s.addSpotLight("grazing spot", kSpotPosition, kSpotTarget, kSpotIntensity, kSpotInner,
                 kSpotOuter);
  s.setCamera(kEye, kLookAt, kYfov);
  return s.take();
}

// Living room lit by one light of each type: x in [-2.4, 2.4], y in [0, 2.4], z in [-1.6, 1.6],
// open towards +Z like the Cornell box, a window in the left wall (x = -2.4).
Scene makeLounge() {
  constexpr float kHalfWidth = 2.4f;
  constexpr float kHalfDepth = 1.6f;
  constexpr float kHeight = 2.4f;
  constexpr float kWallCell = 0.3f;
  constexpr float kFurnitureCell = 0.2f;
  // The window: z in [-1, 0], sill at 0.9 m, lintel at 1.9 m.
  constexpr float kWindowMinZ = -1.0f;
  constexpr float kWindowMaxZ = 0.0f;
  constexpr float kSill = 0.9f;
  constexpr float kLintel = 1.9f;
  constexpr glm::vec3 kPlaster(0.8f, 0.78f, 0.74f);
  constexpr glm::vec3 kWood(0.45f, 0.3f, 0.18f);
  constexpr glm::vec3 kFabric(0.1f, 0.35f, 0.4f);
  constexpr glm::vec3 kLacquer(0.75f, 0.75f, 0.75f);
  constexpr glm::vec3 kRedLacquer(0.5f, 0.1f, 0.08f);
  // Sun 38 degrees above the horizon from the left, travelling slightly towards the open front,
  // so it enters only through the window: a 1 x 1 m patch on the floor at x ~ -1, the rest of
  // the room lit by the lamps and the bounce. 4 W/m^2 on a plane facing it.
  constexpr glm::vec3 kSunDirection(0.62f, -0.62f, 0.2f);
  constexpr float kSunIlluminance = 4.0f;
  // Warm bulb hanging over the right half of the room, 0.8 m below the ceiling: it lights the
  // ceiling, the right wall and the cabinet from inside the room, like a real lamp.
  constexpr glm::vec3 kLampPosition(1.2f, 1.6f, -0.5f);
  constexpr glm::vec3 kLampColour(1.0f, 0.85f, 0.65f);
  constexpr float kLampIntensity = 2.0f;  // W/sr: 2 W/m^2 on the wall 1.2 m away
  // Two ceiling spots: a cool one on the back wall behind the sofa, a red-orange one on the
  // cabinet and the floor in front of it.
  constexpr glm::vec3 kCoolSpotPosition(-0.8f, 2.35f, 0.9f);
  constexpr glm::vec3 kCoolSpotTarget(-0.9f, 0.6f, -1.6f);
  constexpr glm::vec3 kCoolSpotColour(0.55f, 0.7f, 1.0f);
  constexpr glm::vec3 kWarmSpotPosition(1.8f, 2.35f, 1.0f);
  constexpr glm::vec3 kWarmSpotTarget(1.5f, 0.0f, -0.9f);
  constexpr glm::vec3 kWarmSpotColour(1.0f, 0.55f, 0.3f);
  constexpr float kSpotIntensity = 10.0f;  // W/sr: ~3 W/m^2 where each lands, 2 m away
  constexpr float kSpotInner = 0.3f;
  constexpr float kSpotOuter = 0.45f;
  // Outside the open front, framing the room's height; the 2:1 room fills a 16:9 view.
  constexpr glm::vec3 kEye(0.0f, 1.2f, 4.5f);
  constexpr glm::vec3 kLookAt(0.0f, 1.1f, 0.0f);
  constexpr float kYfov = 0.69f;

  ProceduralScene s("lounge");
  const uint32_t plaster = s.addMaterial("plaster", kPlaster, 0.9f, 0.0f);
  const uint32_t wood = s.addMaterial("oiled wood floor", kWood, 0.35f, 0.0f);
  const uint32_t fabric = s.addMaterial("sofa fabric", kFabric, 0.95f, 0.0f);
  const uint32_t lacquer = s.addMaterial("white lacquer", kLacquer, 0.3f, 0.0f);
  const uint32_t redLacquer = s.addMaterial("red lacquer", kRedLacquer, 0.45f, 0.0f);

  const float w = 2.0f * kHalfWidth, d = 2.0f * kHalfDepth;
  const float x0 = -kHalfWidth, z0 = kHalfDepth;  // the left wall's front edge
  s.addRect({x0, 0.0f, z0}, {w, 0.0f, 0.0f}, {0.0f, 0.0f, -d}, wood, kWallCell);
  s.addRect({x0, kHeight, -kHalfDepth}, {w, 0.0f, 0.0f}, {0.0f, 0.0f, d}, plaster, kWallCell);
  s.addRect({x0, 0.0f, -kHalfDepth}, {w, 0.0f, 0.0f}, {0.0f, kHeight, 0.0f}, plaster, kWallCell);
  s.addRect({kHalfWidth, 0.0f, -kHalfDepth}, {0.0f, 0.0f, d}, {0.0f, kHeight, 0.0f}, plaster,
            kWallCell);
  // The left wall in four pieces around the window, all facing +X (into the room).
  const glm::vec3 towardsBack(0.0f, 0.0f, -1.0f), up(0.0f, 1.0f, 0.0f);
  s.addRect({x0, 0.0f, z0}, towardsBack * d, up * kSill, plaster, kWallCell);
  s.addRect({x0, kLintel, z0}, towardsBack * d, up * (kHeight - kLintel), plaster, kWallCell);
  s.addRect({x0, kSill, z0}, towardsBack * (z0 - kWindowMaxZ), up * (kLintel - kSill), plaster,
            kWallCell);
  s.addRect({x0, kSill, kWindowMinZ}, towardsBack * (kWindowMinZ + kHalfDepth),
            up * (kLintel - kSill), plaster, kWallCell);

  s.addBox({-1.0f, 0.0f, -1.2f}, {1.8f, 0.45f, 0.7f}, 0.0f, fabric, kFurnitureCell);   // sofa
  s.addBox({1.7f, 0.0f, -1.3f}, {0.8f, 1.5f, 0.45f}, 0.0f, lacquer, kFurnitureCell);   // cabinet
  s.addBox({0.3f, 0.0f, 0.1f}, {0.9f, 0.4f, 0.6f}, 0.2f, redLacquer, kFurnitureCell);  // table

  s.addPointLight("lamp", kLampPosition, kLampColour, kLampIntensity);
  s.addSpotLight("cool spot", kCoolSpotPosition, kCoolSpotTarget, kSpotIntensity, kSpotInner,
                 kSpotOuter, kCoolSpotColour);
  s.addSpotLight("warm spot", kWarmSpotPosition, kWarmSpotTarget, kSpotIntensity, kSpotInner,
                 kSpotOuter, kWarmSpotColour);
  s.addSun("sun through the window", kSunDirection, kSunIlluminance);
  s.setCamera(kEye, kLookAt, kYfov);
  return s.take();
}

// The Cornell box with `triangles` more in white UV spheres: one on the floor in the spot's
// cone, or (`outside`) a tenth of them there and the rest in a sphere above the ceiling,
// outside the spot's cone and the camera's view.
Scene makeSphereRoom(uint32_t triangles, bool outside, const std::string& name) {
  ProceduralScene s(makeCornell(), name);
  const uint32_t white = s.addMaterial("sphere white", glm::vec3(0.73f), 0.9f, 0.0f);
  const uint32_t inside = outside ? triangles / 10 : triangles;
  s.addSphere({-1.15f, 0.3f, -0.45f}, 0.3f, inside, white);
  if (outside) s.addSphere({0.0f, 3.2f, 1.2f}, 0.6f, triangles - inside, white);
  Scene scene = s.take();
  // Matte, like the scene the scaling targets were set on (docs/performance.md, "Scaling"): no
  // specular lobe anywhere (KHR_materials_specular's factor 0: F0 = F90 = 0), so the planner
  // leaves out the glossy term and the specular VSGL lobes, whose shading costs about 2.5x the
  // diffuse term's per pixel-VSGL pair and would hide what the geometry costs.
  for (Material& m : scene.materials) m.specularFactor = 0.0f;
  return scene;
}

}  // namespace

bool isGeneratedSceneName(const std::string& name) {
  return name.rfind("sphere-room:", 0) == 0 || name.rfind("sphere-room-outside:", 0) == 0;
}

std::vector<std::string> builtinSceneNames() {
  return {"cornell", "atrium", "checker", "lounge"};
}

std::string builtinSceneList() {
  std::string list;
  for (const std::string& name : builtinSceneNames()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

Scene makeBuiltinScene(const std::string& name) {
  if (name == "cornell") return makeCornell();
  if (name == "atrium") return makeAtrium();
  if (name == "checker") return makeChecker();
  if (name == "lounge") return makeLounge();
  if (isGeneratedSceneName(name)) {
    const std::string count = name.substr(name.find(':') + 1);
    char* end = nullptr;
    const unsigned long long n = std::strtoull(count.c_str(), &end, 10);
    if (count.empty() || *end != '\0' || count[0] == '-' || n < 1000 || n > 16000000)
      throw Error("--scene: '" + name + "': the sphere triangle count must be a whole number in " +
                  "[1000, 16000000]");
    return makeSphereRoom(uint32_t(n), name.rfind("sphere-room-outside:", 0) == 0, name);
  }
  throw Error("unknown built-in scene '" + name + "' (choices: " + builtinSceneList() + ")");
}

}  // namespace engine
