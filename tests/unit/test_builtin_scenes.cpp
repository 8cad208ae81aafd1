#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine/builtin_scenes.h"
#include "engine/error.h"
#include "engine/gltf.h"
#include "engine/scene.h"

namespace {

namespace fs = std::filesystem;

constexpr float kTolerance = 1e-5f;

bool contains(const engine::Bounds& b, const glm::vec3& p, float margin = 1e-4f) {
  return glm::all(glm::greaterThanEqual(p, b.min - margin)) &&
         glm::all(glm::lessThanEqual(p, b.max + margin));
}

// Slab test: does the ray origin + t * direction, t > 0, meet the box?
bool rayHitsBox(const glm::vec3& origin, const glm::vec3& direction, const engine::Bounds& b) {
  float tNear = 0.0f;
  float tFar = std::numeric_limits<float>::max();
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(direction[axis]) < 1e-12f) {
      if (origin[axis] < b.min[axis] || origin[axis] > b.max[axis]) return false;
      continue;
    }
    float t0 = (b.min[axis] - origin[axis]) / direction[axis];
    float t1 = (b.max[axis] - origin[axis]) / direction[axis];
    if (t0 > t1) std::swap(t0, t1);
    tNear = std::max(tNear, t0);
    tFar = std::min(tFar, t1);
  }
  return tNear <= tFar;
}

// Nearest triangle hit along a ray (Moeller-Trumbore, both sides), brute force.
std::optional<uint32_t> firstHit(const engine::Scene& scene, const glm::vec3& origin,
                                 const glm::vec3& direction) {
  std::optional<uint32_t> best;
  float bestT = std::numeric_limits<float>::max();
  for (uint32_t t = 0; t < scene.triangleCount(); ++t) {
    const glm::vec3 p0 = scene.positions[scene.indices[3 * t]];
    const glm::vec3 e1 = scene.positions[scene.indices[3 * t + 1]] - p0;
    const glm::vec3 e2 = scene.positions[scene.indices[3 * t + 2]] - p0;
    const glm::vec3 pv = glm::cross(direction, e2);
    const float det = glm::dot(e1, pv);
    if (std::abs(det) < 1e-12f) continue;
    const glm::vec3 tv = origin - p0;
    // A ray through an edge shared by two triangles must hit at least one of them despite
    // rounding, so the inside test is widened by kEdgeSlack (in barycentric units).
    constexpr float kEdgeSlack = 1e-6f;
    const float u = glm::dot(tv, pv) / det;
    if (u < -kEdgeSlack || u > 1.0f + kEdgeSlack) continue;
    const glm::vec3 qv = glm::cross(tv, e1);
    const float v = glm::dot(direction, qv) / det;
    if (v < -kEdgeSlack || u + v > 1.0f + kEdgeSlack) continue;
    const float hit = glm::dot(e2, qv) / det;
    if (hit > 1e-4f && hit < bestT) {
      bestT = hit;
      best = t;
    }
  }
  return best;
}

glm::vec3 faceNormal(const engine::Scene& scene, uint32_t t) {
  const glm::vec3 p0 = scene.positions[scene.indices[3 * t]];
  return glm::normalize(glm::cross(scene.positions[scene.indices[3 * t + 1]] - p0,
                                   scene.positions[scene.indices[3 * t + 2]] - p0));
}

class BuiltinScene : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinScene, IsWellFormed) {
  const engine::Scene scene = engine::makeBuiltinScene(GetParam());
  EXPECT_EQ(scene.source, "builtin:" + GetParam());
  const size_t vertexCount = scene.positions.size();
  ASSERT_GT(vertexCount, 0u);
  ASSERT_EQ(scene.normals.size(), vertexCount);
  ASSERT_EQ(scene.uvs.size(), vertexCount);
  ASSERT_EQ(scene.indices.size() % 3, 0u);
  ASSERT_EQ(scene.triangleMaterial.size(), scene.triangleCount());
  // Tessellated, but small enough for the CPU references to stay fast.
  EXPECT_GE(scene.triangleCount(), 1000u);
  EXPECT_LE(scene.triangleCount(), 20000u);
  for (uint32_t index : scene.indices) ASSERT_LT(index, vertexCount);
  for (const glm::vec3& n : scene.normals) EXPECT_NEAR(glm::length(n), 1.0f, kTolerance);
  ASSERT_FALSE(scene.materials.empty());
  for (uint32_t m : scene.triangleMaterial) ASSERT_LT(m, scene.materials.size());
  for (const engine::Material& m : scene.materials) {
    EXPECT_GE(m.roughnessFactor, 0.0f);
    EXPECT_LE(m.roughnessFactor, 1.0f);
    EXPECT_GE(m.metallicFactor, 0.0f);
    EXPECT_LE(m.metallicFactor, 1.0f);
    EXPECT_TRUE(glm::all(glm::lessThanEqual(m.baseColorFactor, glm::vec4(1.0f))));
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(m.baseColorFactor, glm::vec4(0.0f))));
  }
  // Flat faces: each triangle's counter-clockwise normal is its vertices' normal, and no
  // triangle is degenerate.
  for (uint32_t t = 0; t < scene.triangleCount(); ++t) {
    const glm::vec3 n = faceNormal(scene, t);
    for (uint32_t k = 0; k < 3; ++k) {
      ASSERT_GT(glm::dot(n, scene.normals[scene.indices[3 * t + k]]), 1.0f - 1e-4f) << t;
    }
  }
}

TEST_P(BuiltinScene, LightsAndCameraFrameTheScene) {
  const engine::Scene scene = engine::makeBuiltinScene(GetParam());
  const engine::Bounds bounds = scene.bounds();
  const glm::vec3 size = bounds.max - bounds.min;
  EXPECT_TRUE(glm::all(glm::greaterThan(size, glm::vec3(1.0f))));  // metres: rooms, not
  EXPECT_TRUE(glm::all(glm::lessThan(size, glm::vec3(20.0f))));    // millimetres or stadiums
  EXPECT_GE(bounds.min.y, 0.0f);                                   // +Y up, floor at 0

  ASSERT_FALSE(scene.lights.empty());
  for (const engine::Light& light : scene.lights) {
    EXPECT_NEAR(glm::length(light.direction), 1.0f, kTolerance);
    EXPECT_GT(light.intensity, 0.0f);
    if (light.type != engine::LightType::Directional) {
      EXPECT_TRUE(contains(bounds, light.position)) << light.name;
    }
    if (light.type == engine::LightType::Spot) {
      EXPECT_GE(light.innerConeAngle, 0.0f);
      EXPECT_LT(light.innerConeAngle, light.outerConeAngle);
      EXPECT_LE(light.outerConeAngle, 1.5707964f);
      // The beam lands on the scene.
      EXPECT_TRUE(firstHit(scene, light.position, light.direction).has_value());
    }
  }

  ASSERT_EQ(scene.cameras.size(), 1u);
  const engine::Camera& camera = scene.cameras[0];
  const glm::mat3 rotation(camera.cameraToWorld);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(glm::length(rotation[i]), 1.0f, kTolerance);
    for (int j = i + 1; j < 3; ++j)
      EXPECT_NEAR(glm::dot(rotation[i], rotation[j]), 0.0f, kTolerance);
  }
  EXPECT_NEAR(glm::determinant(rotation), 1.0f, kTolerance);
  EXPECT_NEAR(rotation[0].y, 0.0f, kTolerance);  // level horizon
  const glm::vec3 eye(camera.cameraToWorld[3]);
  const glm::vec3 forward = -rotation[2];
  EXPECT_TRUE(rayHitsBox(eye, forward, bounds));
  EXPECT_TRUE(camera.perspective);
  EXPECT_GT(camera.yfov, 0.3f);
  EXPECT_LT(camera.yfov, 1.6f);

  // Every surface the camera sees (a 7x7 grid of rays over a square view, inset so that no ray
  // runs exactly along an edge) shows its front: the rooms' faces point inwards, the boxes'
  // outwards. Only the sky may be seen: rays that meet nothing must go upwards.
  const float tanHalf = 0.97f * std::tan(0.5f * camera.yfov);
  for (int j = -3; j <= 3; ++j) {
    for (int i = -3; i <= 3; ++i) {
      const glm::vec3 local(tanHalf * static_cast<float>(i) / 3.0f,
                            tanHalf * static_cast<float>(j) / 3.0f, -1.0f);
      const glm::vec3 direction = glm::normalize(rotation * local);
      if (const auto t = firstHit(scene, eye, direction)) {
        EXPECT_LT(glm::dot(faceNormal(scene, *t), direction), 0.0f) << "ray " << i << "," << j;
      } else {
        EXPECT_GT(direction.y, 0.2f) << "ray " << i << "," << j << " escapes sideways";
      }
    }
  }
}

TEST_P(BuiltinScene, RoundTripsThroughGltf) {
  static std::atomic<int> counter{0};
  const fs::path dir =
      fs::temp_directory_path() /
      ("vsgl_builtin_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  fs::create_directories(dir);
  const engine::Scene scene = engine::makeBuiltinScene(GetParam());
  const fs::path path = dir / (GetParam() + ".gltf");
  engine::writeGltf(scene, path.string());
  const engine::Scene back = engine::loadGltf(path.string());
  fs::remove_all(dir);

  ASSERT_EQ(back.triangleCount(), scene.triangleCount());
  EXPECT_EQ(back.triangleMaterial, scene.triangleMaterial);
  for (size_t i = 0; i < scene.indices.size(); ++i) {
    const uint32_t a = scene.indices[i];
    const uint32_t b = back.indices[i];
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(back.positions[b][c], scene.positions[a][c], kTolerance) << i;
      ASSERT_NEAR(back.normals[b][c], scene.normals[a][c], kTolerance) << i;
    }
    ASSERT_NEAR(back.uvs[b].x, scene.uvs[a].x, kTolerance);
    ASSERT_NEAR(back.uvs[b].y, scene.uvs[a].y, kTolerance);
  }
  ASSERT_EQ(back.materials.size(), scene.materials.size());
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const engine::Material& x = scene.materials[m];
    const engine::Material& y = back.materials[m];
    EXPECT_EQ(y.name, x.name);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(y.baseColorFactor[c], x.baseColorFactor[c], kTolerance);
    EXPECT_NEAR(y.metallicFactor, x.metallicFactor, kTolerance);
    EXPECT_NEAR(y.roughnessFactor, x.roughnessFactor, kTolerance);
    EXPECT_EQ(y.baseColorTexture, x.baseColorTexture);
    EXPECT_EQ(y.metallicRoughnessTexture, x.metallicRoughnessTexture);
    EXPECT_EQ(y.doubleSided, x.doubleSided);
  }
  ASSERT_EQ(back.lights.size(), scene.lights.size());
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    const engine::Light& x = scene.lights[l];
    const engine::Light& y = back.lights[l];
    EXPECT_EQ(y.name, x.name);
    EXPECT_EQ(y.type, x.type);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(y.position[c], x.position[c], kTolerance);
      EXPECT_NEAR(y.direction[c], x.direction[c], kTolerance);
      EXPECT_NEAR(y.color[c], x.color[c], kTolerance);
    }
    EXPECT_NEAR(y.intensity, x.intensity, kTolerance);
    EXPECT_NEAR(y.range, x.range, kTolerance);
    if (x.type == engine::LightType::Spot) {
      EXPECT_NEAR(y.innerConeAngle, x.innerConeAngle, kTolerance);
      EXPECT_NEAR(y.outerConeAngle, x.outerConeAngle, kTolerance);
    }
  }
  ASSERT_EQ(back.cameras.size(), scene.cameras.size());
  const engine::Camera& x = scene.cameras[0];
  const engine::Camera& y = back.cameras[0];
  EXPECT_EQ(y.name, x.name);
  EXPECT_EQ(y.perspective, x.perspective);
  EXPECT_NEAR(y.yfov, x.yfov, kTolerance);
  EXPECT_NEAR(y.aspectRatio, x.aspectRatio, kTolerance);
  EXPECT_NEAR(y.znear, x.znear, kTolerance);
  EXPECT_NEAR(y.zfar, x.zfar, kTolerance);
  for (int col = 0; col < 4; ++col) {
    for (int row = 0; row < 4; ++row) {
      EXPECT_NEAR(y.cameraToWorld[col][row], x.cameraToWorld[col][row], kTolerance);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Builtin, BuiltinScene, ::testing::ValuesIn(engine::builtinSceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

TEST(BuiltinScenes, NamesAndUnknownName) {
  EXPECT_EQ(engine::builtinSceneNames(),
            (std::vector<std::string>{"cornell", "atrium", "checker", "lounge"}));
  try {
    engine::makeBuiltinScene("sponza");
    FAIL() << "no error";
  } catch (const engine::Error& e) {
    EXPECT_STREQ(e.what(),
                 "unknown built-in scene 'sponza' (choices: cornell, atrium, checker, lounge)");
  }
}

bool hasMaterial(const engine::Scene& scene, float minRoughness, float maxRoughness) {
  // Only materials some triangle uses count.
  for (uint32_t m : scene.triangleMaterial) {
    const float r = scene.materials[m].roughnessFactor;
    if (r >= minRoughness && r <= maxRoughness) return true;
  }
  return false;
}

TEST(BuiltinScenes, CornellHasSpotAndGlossySurfaces) {
  const engine::Scene scene = engine::makeBuiltinScene("cornell");
  EXPECT_TRUE(std::any_of(scene.lights.begin(), scene.lights.end(), [](const engine::Light& l) {
    return l.type == engine::LightType::Spot;
  }));
  EXPECT_TRUE(hasMaterial(scene, 0.0f, 0.4f));
  EXPECT_TRUE(hasMaterial(scene, 0.8f, 1.0f));
}

TEST(BuiltinScenes, AtriumHasSun) {
  const engine::Scene scene = engine::makeBuiltinScene("atrium");
  EXPECT_TRUE(std::any_of(scene.lights.begin(), scene.lights.end(), [](const engine::Light& l) {
    return l.type == engine::LightType::Directional && l.direction.y < -0.3f;
  }));
}

TEST(BuiltinScenes, CheckerAlternatesGlossyAndRough) {
  const engine::Scene scene = engine::makeBuiltinScene("checker");
  EXPECT_TRUE(hasMaterial(scene, 0.0f, 0.1f));
  EXPECT_TRUE(hasMaterial(scene, 0.8f, 1.0f));
  // Floor triangles (all normals +Y at y = 0): both kinds, in equal numbers.
  size_t glossy = 0;
  size_t rough = 0;
  for (uint32_t t = 0; t < scene.triangleCount(); ++t) {
    if (scene.positions[scene.indices[3 * t]].y != 0.0f || faceNormal(scene, t).y < 0.99f) continue;
    (scene.materials[scene.triangleMaterial[t]].roughnessFactor < 0.1f ? glossy : rough)++;
  }
  EXPECT_GT(glossy, 500u);
  EXPECT_EQ(glossy, rough);
}

TEST(BuiltinScenes, LoungeHasEveryLightTypeAndTheSunEntersByTheWindow) {
  const engine::Scene scene = engine::makeBuiltinScene("lounge");
  const engine::Light* sun = nullptr;
  std::vector<glm::vec3> spotColours;
  int points = 0;
  for (const engine::Light& l : scene.lights) {
    if (l.type == engine::LightType::Directional) sun = &l;
    if (l.type == engine::LightType::Spot) spotColours.push_back(l.color);
    if (l.type == engine::LightType::Point) ++points;
  }
  ASSERT_NE(sun, nullptr);
  EXPECT_EQ(points, 1);
  ASSERT_EQ(spotColours.size(), 2u);
  EXPECT_GT(glm::length(spotColours[0] - spotColours[1]), 0.3f);  // visibly different colours

  // Floor points on a 10 cm grid that see the sun: some do, and each one's ray towards the sun
  // leaves the room through the window in the left wall (x = -2.4, z in [-1, 0], y in
  // [0.9, 1.9]), never through the open front or a wall.
  int lit = 0;
  for (float x = -2.35f; x < 2.4f; x += 0.1f) {
    for (float z = -1.55f; z < 1.6f; z += 0.1f) {
      const glm::vec3 p(x, 1e-3f, z);
      const glm::vec3 towardsSun = -sun->direction;
      if (firstHit(scene, p, towardsSun)) continue;
      ++lit;
      const float t = (-2.4f - p.x) / towardsSun.x;
      const glm::vec3 atWall = p + t * towardsSun;
      EXPECT_GE(atWall.y, 0.9f - 1e-3f) << x << "," << z;
      EXPECT_LE(atWall.y, 1.9f + 1e-3f) << x << "," << z;
      EXPECT_GE(atWall.z, -1.0f - 1e-3f) << x << "," << z;
      EXPECT_LE(atWall.z, 0.0f + 1e-3f) << x << "," << z;
    }
  }
  EXPECT_GT(lit, 40);  // the patch is about 1 m^2: ~100 grid points, less the sofa's shadow
}

TEST(BuiltinScenes, DefaultCameraFramesTheBounds) {
  const engine::Scene scene = engine::makeBuiltinScene("cornell");
  const engine::Camera camera = engine::defaultCamera(scene);
  const engine::Bounds b = scene.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max);
  const float radius = 0.5f * glm::length(b.max - b.min);
  const glm::vec3 eye(camera.cameraToWorld[3]);
  EXPECT_TRUE(camera.perspective);
  EXPECT_EQ(camera.zfar, 0.0f);
  EXPECT_GT(camera.znear, 0.0f);
  EXPECT_EQ(glm::mat3(camera.cameraToWorld), glm::mat3(1.0f));  // looks down -Z
  EXPECT_NEAR(eye.x, centre.x, kTolerance);
  EXPECT_NEAR(eye.y, centre.y, kTolerance);
  EXPECT_GT(eye.z, b.max.z);
  // The bounding sphere fits in the vertical field of view.
  EXPECT_GE(std::asin(radius / glm::length(centre - eye)), 0.0f);
  EXPECT_LE(std::asin(radius / glm::length(centre - eye)), 0.5f * camera.yfov + 1e-5f);
}

// The generated scenes of the scaling measurements: the matte Cornell box plus about N sphere
// triangles (within 1 %: a whole number of stacks; far below 10 000 the smallest sphere, 8 x 16,
// is larger), in the spot's cone or, for the "outside" variant, 90 % of them above the ceiling
// (y > 2 m) where the downward spot cannot reach.
TEST(BuiltinScenes, GeneratedSphereRooms) {
  const engine::Scene cornell = engine::makeBuiltinScene("cornell");
  for (const uint32_t n : {20000u, 100000u}) {
    const engine::Scene inside = engine::makeBuiltinScene("sphere-room:" + std::to_string(n));
    const engine::Scene outside =
        engine::makeBuiltinScene("sphere-room-outside:" + std::to_string(n));
    const double added = double(inside.triangleCount() - cornell.triangleCount());
    EXPECT_NEAR(added, double(n), 0.01 * n + 64) << n;
    EXPECT_NEAR(double(outside.triangleCount() - cornell.triangleCount()), double(n),
                0.01 * n + 128)
        << n;
    uint32_t above = 0;
    for (size_t t = cornell.triangleCount(); t < outside.triangleCount(); ++t) {
      bool all = true;
      for (int k = 0; k < 3; ++k)
        all = all && outside.positions[outside.indices[3 * t + k]].y > 2.0f;
      above += all;
    }
    const double share = double(above) / double(outside.triangleCount() - cornell.triangleCount());
    EXPECT_NEAR(share, 0.9, 0.02) << n;
    EXPECT_EQ(inside.lights.size(), 1u);
    for (const engine::Scene* scene : {&inside, &outside})
      for (const engine::Material& m : scene->materials)
        EXPECT_EQ(m.specularFactor, 0.0f) << m.name << ": the generated rooms are matte";
    EXPECT_EQ(inside.source, "builtin:sphere-room:" + std::to_string(n));
    EXPECT_TRUE(engine::isGeneratedSceneName("sphere-room:" + std::to_string(n)));
  }
  for (const std::string bad : {"sphere-room:", "sphere-room:999", "sphere-room:12x",
                                "sphere-room:-5", "sphere-room:16000001"}) {
    try {
      engine::makeBuiltinScene(bad);
      ADD_FAILURE() << bad;
    } catch (const engine::Error& e) {
      EXPECT_NE(std::string(e.what()).find("whole number in [1000, 16000000]"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
