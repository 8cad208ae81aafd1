#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/builtin_scenes.h"
#include "engine/error.h"
#include "engine/gltf.h"
#include "engine/scene.h"
#include "engine/view.h"
#include "test_files.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Small glTFs written by tests/data/gltf/make_test_gltfs.py (see its docstrings).
const fs::path kGltfData = fs::path(VSGL_TEST_DATA) / "gltf";

// A fresh directory under the system temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() /
            ("vsgl_gltf_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  fs::path operator/(const std::string& name) const { return path_ / name; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

using test_files::readBytes;
using test_files::writeBytes;

std::string readText(const fs::path& path) {
  const std::vector<uint8_t> bytes = readBytes(path);
  return {bytes.begin(), bytes.end()};
}

void writeText(const fs::path& path, const std::string& text) {
  writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

std::vector<uint8_t> base64Decode(const std::string& text) {
  std::vector<uint8_t> out;
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    int value;
    if (c >= 'A' && c <= 'Z')
      value = c - 'A';
    else if (c >= 'a' && c <= 'z')
      value = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      value = c - '0' + 52;
    else if (c == '+')
      value = 62;
    else if (c == '/')
      value = 63;
    else
      continue;  // '=' padding
    bits = (bits << 6) | static_cast<uint32_t>(value);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<uint8_t>((bits >> count) & 0xFF));
    }
  }
  return out;
}

std::vector<uint8_t> decodeDataUri(const std::string& uri) {
  return base64Decode(uri.substr(uri.find(',') + 1));
}

void appendU32(std::vector<uint8_t>& out, uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(value >> (8 * i)));
}

// Converts a .gltf with one buffer (a data URI or a file beside it) into a .glb: the buffer
// becomes the BIN chunk, and data-URI images move into it behind bufferViews (the way exporters
// embed images).
void convertToGlb(const fs::path& gltfPath, const fs::path& glbPath) {
  json gltf = json::parse(readText(gltfPath));
  const std::string bufferUri = gltf["buffers"][0]["uri"];
  std::vector<uint8_t> bin = bufferUri.rfind("data:", 0) == 0
                                 ? decodeDataUri(bufferUri)
                                 : readBytes(gltfPath.parent_path() / bufferUri);
  gltf["buffers"][0].erase("uri");
  if (gltf.contains("images")) {
    for (json& image : gltf["images"]) {
      const std::string uri = image["uri"];
      if (uri.rfind("data:", 0) != 0) continue;
      const std::vector<uint8_t> bytes = decodeDataUri(uri);
      while (bin.size() % 4 != 0) bin.push_back(0);
      gltf["bufferViews"].push_back(
          {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
      bin.insert(bin.end(), bytes.begin(), bytes.end());
      image.erase("uri");
      image["bufferView"] = gltf["bufferViews"].size() - 1;
      image["mimeType"] = "image/png";
    }
  }
  gltf["buffers"][0]["byteLength"] = bin.size();
  std::string text = gltf.dump();
  while (text.size() % 4 != 0) text += ' ';
  while (bin.size() % 4 != 0) bin.push_back(0);

  std::vector<uint8_t> glb;
  appendU32(glb, 0x46546C67);  // "glTF"
  appendU32(glb, 2);
  appendU32(glb, static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  appendU32(glb, static_cast<uint32_t>(text.size()));
  appendU32(glb, 0x4E4F534A);  // "JSON"
  glb.insert(glb.end(), text.begin(), text.end());
  appendU32(glb, static_cast<uint32_t>(bin.size()));
  appendU32(glb, 0x004E4942);  // "BIN\0"
  glb.insert(glb.end(), bin.begin(), bin.end());
  writeBytes(glbPath, glb);
}

// Loading `path` must throw engine::Error: one line, naming the file, containing `phrase`.
void expectLoadError(const fs::path& path, const std::string& phrase) {
  SCOPED_TRACE(path.string());
  try {
    engine::loadGltf(path.string());
    ADD_FAILURE() << "no error for " << path;
  } catch (const engine::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    EXPECT_NE(message.find(phrase), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.find('\r'), std::string::npos) << message;
  }
}

// Either a clean load or an engine::Error; anything else (or a crash) fails.
void expectLoadsOrClean(const fs::path& path) {
  try {
    engine::loadGltf(path.string());
  } catch (const engine::Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

void expectVec3Near(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

glm::vec3 corner(const engine::Scene& scene, uint32_t triangle, int k) {
  return scene.positions[scene.indices[3 * triangle + static_cast<uint32_t>(k)]];
}

glm::vec3 geometricNormal(const engine::Scene& scene, uint32_t triangle) {
  const glm::vec3 p0 = corner(scene, triangle, 0);
  return glm::normalize(
      glm::cross(corner(scene, triangle, 1) - p0, corner(scene, triangle, 2) - p0));
}

TEST(GltfLoader, TriangleWithSpotLightAndCamera) {
  const fs::path path = kGltfData / "triangle_spot.gltf";
  const engine::Scene scene = engine::loadGltf(path.string());
  EXPECT_EQ(scene.source, path.string());
  ASSERT_EQ(scene.triangleCount(), 1u);
  ASSERT_EQ(scene.positions.size(), 3u);
  expectVec3Near(corner(scene, 0, 0), {0, 0, 0});
  expectVec3Near(corner(scene, 0, 1), {1, 0, 0});
  expectVec3Near(corner(scene, 0, 2), {0, 1, 0});
  for (const glm::vec3& n : scene.normals) expectVec3Near(n, {0, 0, 1});
  EXPECT_EQ(scene.uvs[scene.indices[1]], glm::vec2(1, 0));

  ASSERT_EQ(scene.materials.size(), 1u);  // every primitive has a material: no default added
  const engine::Material& m = scene.materials[0];
  EXPECT_EQ(m.name, "paint");
  EXPECT_EQ(m.baseColorFactor, glm::vec4(0.8f, 0.2f, 0.1f, 1.0f));
  EXPECT_FLOAT_EQ(m.metallicFactor, 0.25f);
  EXPECT_FLOAT_EQ(m.roughnessFactor, 0.4f);
  EXPECT_EQ(m.baseColorTexture, -1);
  EXPECT_TRUE(m.doubleSided);
  EXPECT_EQ(scene.triangleMaterial, std::vector<uint32_t>{0});

  ASSERT_EQ(scene.lights.size(), 1u);
  const engine::Light& light = scene.lights[0];
  EXPECT_EQ(light.name, "spot");
  EXPECT_EQ(light.type, engine::LightType::Spot);
  expectVec3Near(light.position, {0, 0, 2});
  expectVec3Near(light.direction, {0, 0, -1});
  expectVec3Near(light.color, {1.0f, 0.9f, 0.8f});
  EXPECT_FLOAT_EQ(light.intensity, 20.0f);
  EXPECT_FLOAT_EQ(light.range, 10.0f);
  EXPECT_FLOAT_EQ(light.innerConeAngle, 0.3f);
  EXPECT_FLOAT_EQ(light.outerConeAngle, 0.5f);

  ASSERT_EQ(scene.cameras.size(), 1u);
  const engine::Camera& camera = scene.cameras[0];
  EXPECT_EQ(camera.name, "cam");
  EXPECT_TRUE(camera.perspective);
  EXPECT_FLOAT_EQ(camera.yfov, 0.7f);
  EXPECT_FLOAT_EQ(camera.aspectRatio, 1.5f);
  EXPECT_FLOAT_EQ(camera.znear, 0.1f);
  EXPECT_EQ(camera.zfar, 0.0f);  // absent = infinite
  EXPECT_EQ(camera.cameraToWorld, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5)));
}

TEST(GltfLoader, NodeHierarchyBakesWorldTransforms) {
  const engine::Scene scene = engine::loadGltf((kGltfData / "hierarchy.gltf").string());
  // Parent: translate (1,2,3) * rotate 90 deg about +Y * scale 2; child: translate (1,0,0).
  // Rotating (x,y,z) by 90 deg about +Y gives (z, y, -x).
  const auto expected = [](glm::vec3 p) {
    const glm::vec3 q = 2.0f * (p + glm::vec3(1, 0, 0));
    return glm::vec3(q.z, q.y, -q.x) + glm::vec3(1, 2, 3);
  };
  ASSERT_EQ(scene.triangleCount(), 2u);  // the child instance, then the matrix-node instance
  const glm::vec3 triangle[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int k = 0; k < 3; ++k) {
    expectVec3Near(corner(scene, 0, k), expected(triangle[k]));
    expectVec3Near(corner(scene, 1, k), triangle[k] + glm::vec3(0, 0, -10));
  }
  expectVec3Near(expected(triangle[0]), {1, 2, 1});  // the formula itself, worked by hand
  for (int k = 0; k < 3; ++k) {
    expectVec3Near(scene.normals[scene.indices[static_cast<size_t>(k)]], {1, 0, 0});
    expectVec3Near(scene.normals[scene.indices[3 + static_cast<size_t>(k)]], {0, 0, 1});
  }
  // No material on the primitive: the documented default is appended once.
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].baseColorFactor, glm::vec4(1.0f));
  EXPECT_EQ(scene.materials[0].metallicFactor, 0.0f);
  EXPECT_EQ(scene.materials[0].roughnessFactor, 0.5f);
  EXPECT_EQ(scene.triangleMaterial, (std::vector<uint32_t>{0, 0}));

  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, engine::LightType::Point);
  EXPECT_FLOAT_EQ(scene.lights[0].intensity, 5.0f);
  expectVec3Near(scene.lights[0].color, {1, 1, 1});
  expectVec3Near(scene.lights[0].position, {1, 2, 3});
  expectVec3Near(scene.lights[0].direction, {-1, 0, 0});  // -Z rotated

  ASSERT_EQ(scene.cameras.size(), 1u);
  const engine::Camera& camera = scene.cameras[0];
  EXPECT_FALSE(camera.perspective);
  EXPECT_FLOAT_EQ(camera.xmag, 2.0f);
  EXPECT_FLOAT_EQ(camera.ymag, 1.5f);
  EXPECT_FLOAT_EQ(camera.znear, 0.5f);
  EXPECT_FLOAT_EQ(camera.zfar, 50.0f);
  // The parent's scale 2 is removed: a rotation plus the translation.
  expectVec3Near(glm::vec3(camera.cameraToWorld[0]), {0, 0, -1});
  expectVec3Near(glm::vec3(camera.cameraToWorld[1]), {0, 1, 0});
  expectVec3Near(glm::vec3(camera.cameraToWorld[2]), {1, 0, 0});
  expectVec3Near(glm::vec3(camera.cameraToWorld[3]), {1, 2, 3});
}

TEST(GltfLoader, GeneratesAreaWeightedNormals) {
  const engine::Scene scene = engine::loadGltf((kGltfData / "no_normals.gltf").string());
  ASSERT_EQ(scene.triangleCount(), 4u);
  ASSERT_EQ(scene.positions.size(), 8u);
  // Face normals (cross products, length = twice the area): A = (-1,2,0) per triangle, B =
  // (1,1,0). The ridge vertices are duplicated but share positions, so each ridge position sums
  // every triangle touching it: (0,1,0) touches A twice and B once, (0,1,-1) A once and B twice.
  const glm::vec3 faceA = glm::normalize(glm::vec3(-1, 2, 0));
  const glm::vec3 faceB = glm::normalize(glm::vec3(1, 1, 0));
  const glm::vec3 ridgeFront = glm::normalize(glm::vec3(-1, 5, 0));
  const glm::vec3 ridgeBack = glm::normalize(glm::vec3(1, 4, 0));
  const glm::vec3 expected[8] = {faceA,      faceA,     ridgeFront, ridgeBack,
                                 ridgeFront, ridgeBack, faceB,      faceB};
  for (size_t v = 0; v < 8; ++v) {
    SCOPED_TRACE(v);
    expectVec3Near(scene.normals[v], expected[v]);
  }
  for (const glm::vec2& uv : scene.uvs) EXPECT_EQ(uv, glm::vec2(0.0f));
}

TEST(GltfLoader, StripsAndFansBecomeCounterClockwiseTriangles) {
  const engine::Scene scene = engine::loadGltf((kGltfData / "strip_fan.gltf").string());
  ASSERT_EQ(scene.triangleCount(), 4u);
  float area = 0.0f;
  for (uint32_t t = 0; t < 4; ++t) {
    expectVec3Near(geometricNormal(scene, t), {0, 0, 1});
    const glm::vec3 p0 = corner(scene, t, 0);
    area += 0.5f * glm::length(glm::cross(corner(scene, t, 1) - p0, corner(scene, t, 2) - p0));
  }
  EXPECT_NEAR(area, 2.0f, 1e-6f);  // two unit squares
}

TEST(GltfLoader, MirroredNodeFlipsWinding) {
  const engine::Scene scene = engine::loadGltf((kGltfData / "mirrored.gltf").string());
  ASSERT_EQ(scene.triangleCount(), 1u);
  expectVec3Near(scene.positions[1], {-1, 0, 0});
  // Without the flip the mirrored triangle would be clockwise seen from +Z.
  expectVec3Near(geometricNormal(scene, 0), {0, 0, 1});
  for (const glm::vec3& n : scene.normals) expectVec3Near(n, {0, 0, 1});
}

void expectCheckerTexture(const engine::Texture& texture) {
  ASSERT_EQ(texture.width, 2);
  ASSERT_EQ(texture.height, 2);
  const std::vector<uint8_t> expected = {255, 0, 0,   255, 0,   255, 0,   255,
                                         0,   0, 255, 255, 255, 255, 255, 255};
  EXPECT_EQ(texture.rgba8, expected);
}

TEST(GltfLoader, DecodesTexturesIndexedLikeImages) {
  const fs::path path = kGltfData / "textured.gltf";
  const engine::Scene scene = engine::loadGltf(path.string());
  ASSERT_EQ(scene.textures.size(), 2u);
  expectCheckerTexture(scene.textures[0]);
  expectCheckerTexture(scene.textures[1]);
  EXPECT_EQ(scene.textures[0].name, "checker2x2.png");
  EXPECT_EQ(scene.textures[1].name, "textured.gltf#image1");
  // glTF texture 0 uses image 1, texture 1 uses image 0.
  EXPECT_EQ(scene.materials[0].baseColorTexture, 1);
  EXPECT_EQ(scene.materials[0].metallicRoughnessTexture, 0);
  // Normalized u16 UVs.
  EXPECT_EQ(scene.uvs[1], glm::vec2(1, 0));
  EXPECT_EQ(scene.uvs[2], glm::vec2(0, 1));
}

TEST(GltfLoader, GlbLoadsLikeGltf) {
  TempDir dir;
  for (const char* name : {"hierarchy", "textured"}) {
    SCOPED_TRACE(name);
    const fs::path gltfPath = kGltfData / (std::string(name) + ".gltf");
    const fs::path glbPath = dir / (std::string(name) + ".glb");
    convertToGlb(gltfPath, glbPath);
    fs::copy_file(kGltfData / "checker2x2.png", dir / "checker2x2.png",
                  fs::copy_options::overwrite_existing);
    const engine::Scene a = engine::loadGltf(gltfPath.string());
    const engine::Scene b = engine::loadGltf(glbPath.string());
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.uvs, b.uvs);
    EXPECT_EQ(a.indices, b.indices);
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (size_t i = 0; i < a.textures.size(); ++i)
      EXPECT_EQ(a.textures[i].rgba8, b.textures[i].rgba8);
    EXPECT_EQ(a.lights.size(), b.lights.size());
    EXPECT_EQ(a.cameras.size(), b.cameras.size());
  }
  // The embedded image is named after the .glb.
  EXPECT_EQ(engine::loadGltf((dir / "textured.glb").string()).textures[1].name,
            "textured.glb#image1");
}

TEST(GltfWriter, WritesTexturesAsPngBesideTheGltf) {
  engine::Scene scene = engine::loadGltf((kGltfData / "textured.gltf").string());
  TempDir dir;
  const fs::path path = dir / "out.gltf";
  engine::writeGltf(scene, path.string());
  EXPECT_TRUE(fs::is_regular_file(dir / "out_tex0.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "out_tex1.png"));
  // Nothing but the .gltf and its textures: the temporary file was renamed into place.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 3);
  // The buffer is embedded: the .gltf alone (plus PNGs) is the whole scene.
  EXPECT_NE(readText(path).find("data:application/octet-stream;base64,"), std::string::npos);
  const engine::Scene back = engine::loadGltf(path.string());
  ASSERT_EQ(back.textures.size(), 2u);
  expectCheckerTexture(back.textures[0]);
  expectCheckerTexture(back.textures[1]);
  EXPECT_EQ(back.textures[0].name, "out_tex0.png");
  EXPECT_EQ(back.materials[0].baseColorTexture, 1);
  EXPECT_EQ(back.materials[0].metallicRoughnessTexture, 0);
  EXPECT_EQ(back.uvs, scene.uvs);
}

// Cameras and light directions cross a written file bit for bit, built-in scenes' and ones a host
// placed at odd angles alike (vsgl_viewer's screenshots rely on it: vsgl_render of the .gltf must
// render the frame the viewer showed). A skewed and scaled camera node is still made rigid.
TEST(GltfWriter, CamerasAndLightDirectionsReadBackBitForBit) {
  for (const std::string& name : engine::builtinSceneNames()) {
    engine::Scene scene = engine::makeBuiltinScene(name);
    // A camera turned by odd angles, as an orbit leaves it, and lights turned likewise.
    engine::Camera turned = scene.cameras.front();
    const glm::vec3 eye(1.234567f, 2.345678f, 3.456789f);
    const glm::vec3 forward = glm::normalize(glm::vec3(-0.3141593f, -0.2718282f, -0.9f));
    turned.cameraToWorld = glm::inverse(engine::lookAlong(eye, forward, glm::vec3(0, 1, 0)));
    turned.name = "turned";
    scene.cameras.push_back(turned);
    for (engine::Light& l : scene.lights)
      l.direction = glm::normalize(l.direction + glm::vec3(0.123457f, -0.0312f, 0.07f));
    TempDir dir;
    engine::writeGltf(scene, (dir / "back.gltf").string());
    const engine::Scene back = engine::loadGltf((dir / "back.gltf").string());
    ASSERT_EQ(back.cameras.size(), scene.cameras.size()) << name;
    for (size_t c = 0; c < scene.cameras.size(); ++c)
      EXPECT_EQ(back.cameras[c].cameraToWorld, scene.cameras[c].cameraToWorld)
          << name << " camera " << c;
    ASSERT_EQ(back.lights.size(), scene.lights.size()) << name;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
      if (scene.lights[i].type == engine::LightType::Point) continue;  // no direction
      EXPECT_EQ(back.lights[i].direction, scene.lights[i].direction) << name << " light " << i;
    }
  }
  // Not rigid: columns scaled by 2 and y skewed towards z; the view axis keeps its direction.
  glm::mat4 skewed(1.0f);
  skewed[0] = glm::vec4(2.0f, 0.0f, 0.0f, 0.0f);
  skewed[1] = glm::vec4(0.0f, 2.0f, 0.5f, 0.0f);
  skewed[2] = glm::vec4(0.0f, 0.0f, 2.0f, 0.0f);
  const std::optional<glm::mat4> rigid = engine::rigidCameraFrame(skewed);
  ASSERT_TRUE(rigid.has_value());
  EXPECT_EQ((*rigid)[2], glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
  EXPECT_EQ((*rigid)[1], glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
  EXPECT_EQ((*rigid)[0], glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  EXPECT_FALSE(engine::rigidCameraFrame(glm::mat4(0.0f)).has_value());
  EXPECT_FALSE(engine::fileLightDirection(glm::vec3(0.0f)).has_value());
  EXPECT_EQ(*engine::fileLightDirection(glm::vec3(0.0f, -3.0f, 0.0f)), glm::vec3(0, -1, 0));
}

// KHR_texture_transform's example: offset (0, 1), rotation pi/2 and scale 0.5 take the unit
// square onto the image's lower-left quadrant, turned clockwise (the result's top-left corner
// shows the quadrant's bottom-left one). Exact in double up to cos(pi/2)'s rounding.
TEST(TextureTransform, MapsAsTheExtensionsExample) {
  const engine::TextureTransform t{{0.0f, 1.0f}, 1.57079632679f, {0.5f, 0.5f}};
  auto map = [&](double u, double v) {
    return glm::dvec2(glm::dot(t.rowU(), glm::dvec3(u, v, 1.0)),
                      glm::dot(t.rowV(), glm::dvec3(u, v, 1.0)));
  };
  const std::pair<glm::dvec2, glm::dvec2> corners[] = {
      {{0, 0}, {0, 1}}, {{1, 0}, {0, 0.5}}, {{0, 1}, {0.5, 1}}, {{1, 1}, {0.5, 0.5}}};
  for (const auto& [from, to] : corners) {
    const glm::dvec2 got = map(from.x, from.y);
    EXPECT_NEAR(got.x, to.x, 1e-7) << from.x << "," << from.y;
    EXPECT_NEAR(got.y, to.y, 1e-7) << from.x << "," << from.y;
  }
  EXPECT_TRUE(engine::TextureTransform{}.identity());
  EXPECT_EQ(engine::TextureTransform{}.rowU(), glm::dvec3(1, 0, 0));
  EXPECT_EQ(engine::TextureTransform{}.rowV(), glm::dvec3(0, 1, 0));
}

// The extension on each texture is read, written back where it is not the identity (and
// listed in extensionsUsed), and refused with its field when malformed.
TEST(GltfLoader, ReadsAndWritesKhrTextureTransform) {
  TempDir dir;
  fs::copy_file(kGltfData / "checker2x2.png", dir / "checker2x2.png");
  json gltf = json::parse(readText(kGltfData / "textured.gltf"));
  json& pbr = gltf["materials"][0]["pbrMetallicRoughness"];
  pbr["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {
      {"offset", {0.25, -0.5}}, {"rotation", 0.5}, {"scale", {2.0, 3.0}}};
  gltf["extensionsUsed"].push_back("KHR_texture_transform");
  writeText(dir / "transform.gltf", gltf.dump());
  const engine::Scene scene = engine::loadGltf((dir / "transform.gltf").string());
  EXPECT_TRUE(scene.warnings.empty());
  const engine::TextureTransform& t = scene.materials[0].baseColorTransform;
  EXPECT_EQ(t.offset, glm::vec2(0.25f, -0.5f));
  EXPECT_EQ(t.rotation, 0.5f);
  EXPECT_EQ(t.scale, glm::vec2(2.0f, 3.0f));
  EXPECT_TRUE(scene.materials[0].metallicRoughnessTransform.identity());

  engine::writeGltf(scene, (dir / "back.gltf").string());
  const json written = json::parse(readText(dir / "back.gltf"));
  EXPECT_NE(std::find(written["extensionsUsed"].begin(), written["extensionsUsed"].end(),
                      "KHR_texture_transform"),
            written["extensionsUsed"].end());
  const engine::Scene back = engine::loadGltf((dir / "back.gltf").string());
  EXPECT_EQ(back.materials[0].baseColorTransform.offset, t.offset);
  EXPECT_EQ(back.materials[0].baseColorTransform.rotation, t.rotation);
  EXPECT_EQ(back.materials[0].baseColorTransform.scale, t.scale);
  EXPECT_TRUE(back.materials[0].metallicRoughnessTransform.identity());

  pbr["baseColorTexture"]["extensions"]["KHR_texture_transform"]["rotation"] = "half";
  writeText(dir / "bad_rotation.gltf", gltf.dump());
  expectLoadError(dir / "bad_rotation.gltf",
                  "material 0 baseColorTexture KHR_texture_transform rotation must be a finite "
                  "number");
  pbr["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {{"texCoord", 0.5}};
  writeText(dir / "bad_texcoord.gltf", gltf.dump());
  expectLoadError(dir / "bad_texcoord.gltf",
                  "material 0 baseColorTexture KHR_texture_transform texCoord must be an integer");
}

// Textures on TEXCOORD_1: textured.gltf with a second set (0.5, 0.5), (0.75, 0.5), (0.5, 0.75)
// in a buffer file of its own. The vertices carry the set the material's textures sample; where
// the two textures sample different sets the base colour's is kept and the metallic-roughness
// texture skipped with a warning; a set the primitive lacks is refused.
// normalTexture: its image, scale and KHR_texture_transform are read and written back; on
// another coordinate set than the base colour it is skipped with a warning; a non-finite scale
// is refused. (What it does to the normals: tests/gpu/test_gbuffer.cpp.)
TEST(GltfLoader, ReadsAndWritesNormalTextures) {
  TempDir dir;
  fs::copy_file(kGltfData / "checker2x2.png", dir / "checker2x2.png");
  json gltf = json::parse(readText(kGltfData / "textured.gltf"));
  gltf["materials"][0]["normalTexture"] = {
      {"index", 1},
      {"scale", 0.75},
      {"extensions", {{"KHR_texture_transform", {{"scale", {2.0, 2.0}}}}}}};
  gltf["extensionsUsed"].push_back("KHR_texture_transform");
  writeText(dir / "normal.gltf", gltf.dump());
  const engine::Scene scene = engine::loadGltf((dir / "normal.gltf").string());
  EXPECT_TRUE(scene.warnings.empty());
  const engine::Material& m = scene.materials[0];
  EXPECT_EQ(m.normalTexture, m.metallicRoughnessTexture);  // texture 1 in both roles
  EXPECT_EQ(m.normalScale, 0.75f);
  EXPECT_EQ(m.normalTransform.scale, glm::vec2(2.0f));

  engine::writeGltf(scene, (dir / "back.gltf").string());
  const engine::Scene back = engine::loadGltf((dir / "back.gltf").string());
  EXPECT_EQ(back.materials[0].normalTexture, back.materials[0].metallicRoughnessTexture);
  EXPECT_EQ(back.materials[0].normalScale, 0.75f);
  EXPECT_EQ(back.materials[0].normalTransform.scale, glm::vec2(2.0f));

  gltf["materials"][0]["normalTexture"]["texCoord"] = 1;
  gltf["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] =
      gltf["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"];
  writeText(dir / "other_set.gltf", gltf.dump());
  const engine::Scene other = engine::loadGltf((dir / "other_set.gltf").string());
  ASSERT_EQ(other.warnings.size(), 1u);
  EXPECT_NE(other.warnings[0].find("material 0 normalTexture: skipped (it samples TEXCOORD_1"),
            std::string::npos)
      << other.warnings[0];
  EXPECT_EQ(other.materials[0].normalTexture, -1);
}

// Emission: emissiveFactor times KHR_materials_emissive_strength, the emissive texture and its
// transform are read and written back (a factor above 1 as the strength); an emissive texture on
// another coordinate set drops the emission with a warning; a negative strength is refused.
TEST(GltfLoader, ReadsAndWritesEmission) {
  TempDir dir;
  fs::copy_file(kGltfData / "checker2x2.png", dir / "checker2x2.png");
  json gltf = json::parse(readText(kGltfData / "textured.gltf"));
  json& material = gltf["materials"][0];
  material["emissiveFactor"] = {0.25, 0.5, 1.0};
  material["emissiveTexture"] = {{"index", 0}};
  material["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", 4.0}};
  gltf["extensionsUsed"].push_back("KHR_materials_emissive_strength");
  writeText(dir / "emissive.gltf", gltf.dump());
  const engine::Scene scene = engine::loadGltf((dir / "emissive.gltf").string());
  EXPECT_TRUE(scene.warnings.empty());
  EXPECT_EQ(scene.materials[0].emissiveFactor, glm::vec3(1.0f, 2.0f, 4.0f));
  EXPECT_EQ(scene.materials[0].emissiveTexture, scene.materials[0].baseColorTexture);

  engine::writeGltf(scene, (dir / "back.gltf").string());
  const json written = json::parse(readText(dir / "back.gltf"));
  EXPECT_EQ(
      written["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"],
      4.0);
  const engine::Scene back = engine::loadGltf((dir / "back.gltf").string());
  EXPECT_EQ(back.materials[0].emissiveFactor, glm::vec3(1.0f, 2.0f, 4.0f));
  EXPECT_EQ(back.materials[0].emissiveTexture, back.materials[0].baseColorTexture);

  material["emissiveTexture"]["texCoord"] = 1;
  gltf["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] =
      gltf["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"];
  writeText(dir / "other_set.gltf", gltf.dump());
  const engine::Scene other = engine::loadGltf((dir / "other_set.gltf").string());
  ASSERT_EQ(other.warnings.size(), 1u);
  EXPECT_NE(other.warnings[0].find("material 0 emissiveTexture (and the emission): skipped"),
            std::string::npos)
      << other.warnings[0];
  EXPECT_EQ(other.materials[0].emissiveFactor, glm::vec3(0.0f));
  EXPECT_EQ(other.materials[0].emissiveTexture, -1);

  material["emissiveTexture"]["texCoord"] = 0;
  material["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = -1.0;
  writeText(dir / "negative.gltf", gltf.dump());
  expectLoadError(dir / "negative.gltf", "emissiveStrength must be a finite number >= 0");
}

TEST(GltfLoader, ReadsAndWritesAlphaModes) {
  const engine::Scene scene = engine::loadGltf((kGltfData / "alpha_mask.gltf").string());
  EXPECT_TRUE(scene.warnings.empty());
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[0].alphaCutoff, 0.0f);  // OPAQUE
  EXPECT_EQ(scene.materials[1].alphaCutoff, 0.5f);
  EXPECT_GE(scene.materials[1].baseColorTexture, 0);

  TempDir dir;
  engine::writeGltf(scene, (dir / "back.gltf").string());
  const json written = json::parse(readText(dir / "back.gltf"));
  EXPECT_EQ(written["materials"][1]["alphaMode"], "MASK");
  EXPECT_EQ(written["materials"][1]["alphaCutoff"], 0.5);
  EXPECT_FALSE(written["materials"][0].contains("alphaMode"));
  EXPECT_EQ(engine::loadGltf((dir / "back.gltf").string()).materials[1].alphaCutoff, 0.5f);

  json gltf = json::parse(readText(kGltfData / "alpha_mask.gltf"));
  gltf["materials"][1].erase("alphaCutoff");  // MASK's default cutoff is 0.5
  gltf["materials"][0]["alphaMode"] = "BLEND";
  writeText(dir / "blend.gltf", gltf.dump());
  const engine::Scene blend = engine::loadGltf((dir / "blend.gltf").string());
  EXPECT_EQ(blend.materials[1].alphaCutoff, 0.5f);
  EXPECT_EQ(blend.materials[0].alphaCutoff, 0.0f);
  ASSERT_EQ(blend.warnings.size(), 1u);
  EXPECT_NE(blend.warnings[0].find("material 'floor' alphaMode BLEND: rendered opaque"),
            std::string::npos)
      << blend.warnings[0];

  gltf["materials"][0]["alphaMode"] = "CUTOUT";
  writeText(dir / "unknown.gltf", gltf.dump());
  expectLoadError(dir / "unknown.gltf", "alphaMode must be OPAQUE, MASK or BLEND (got 'CUTOUT')");
  gltf["materials"][0]["alphaMode"] = "MASK";
  gltf["materials"][0]["alphaCutoff"] = -0.25;
  writeText(dir / "negative.gltf", gltf.dump());
  expectLoadError(dir / "negative.gltf", "alphaCutoff must be a finite number >= 0");
}

TEST(GltfLoader, TexturesOnASecondCoordinateSet) {
  TempDir dir;
  fs::copy_file(kGltfData / "checker2x2.png", dir / "checker2x2.png");
  const std::vector<float> second = {0.5f, 0.5f, 0.75f, 0.5f, 0.5f, 0.75f};
  std::vector<uint8_t> bytes(second.size() * sizeof(float));
  std::memcpy(bytes.data(), second.data(), bytes.size());
  writeBytes(dir / "second.bin", bytes);
  json base = json::parse(readText(kGltfData / "textured.gltf"));
  base["buffers"].push_back({{"uri", "second.bin"}, {"byteLength", bytes.size()}});
  base["bufferViews"].push_back(
      {{"buffer", base["buffers"].size() - 1}, {"byteLength", bytes.size()}});
  base["accessors"].push_back({{"bufferView", base["bufferViews"].size() - 1},
                               {"componentType", 5126},
                               {"count", 3},
                               {"type", "VEC2"}});
  base["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = base["accessors"].size() - 1;
  const auto load = [&](const std::string& name, const std::function<void(json&)>& edit) {
    json gltf = base;
    edit(gltf);
    writeText(dir / name, gltf.dump());
    return engine::loadGltf((dir / name).string());
  };
  const auto expectSecondSet = [&](const engine::Scene& scene) {
    ASSERT_EQ(scene.uvs.size(), 3u);
    for (size_t v = 0; v < 3; ++v)
      EXPECT_EQ(scene.uvs[v], glm::vec2(second[2 * v], second[2 * v + 1])) << "vertex " << v;
  };

  const engine::Scene both = load("both.gltf", [](json& g) {
    g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
    g["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"]["texCoord"] = 1;
  });
  EXPECT_TRUE(both.warnings.empty());
  expectSecondSet(both);
  EXPECT_GE(both.materials[0].metallicRoughnessTexture, 0);

  const engine::Scene mixed = load("mixed.gltf", [](json& g) {
    g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]
     ["KHR_texture_transform"] = {{"texCoord", 1}};
    g["extensionsUsed"].push_back("KHR_texture_transform");
  });
  ASSERT_EQ(mixed.warnings.size(), 1u);
  EXPECT_NE(mixed.warnings[0].find("material 0 metallicRoughnessTexture: skipped (it samples "
                                   "TEXCOORD_0, the material's other textures TEXCOORD_1"),
            std::string::npos)
      << mixed.warnings[0];
  expectSecondSet(mixed);
  EXPECT_EQ(mixed.materials[0].metallicRoughnessTexture, -1);
  EXPECT_GE(mixed.materials[0].baseColorTexture, 0);

  json lacking = base;
  lacking["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 2;
  writeText(dir / "lacking.gltf", lacking.dump());
  expectLoadError(dir / "lacking.gltf",
                  "primitive 0: its material's textures sample TEXCOORD_2, which the primitive "
                  "lacks");
}

// KHR_materials_specular's factors are read (textures are not supported), written back only
// where they differ from the defaults, and listed in extensionsUsed.
TEST(GltfLoader, ReadsAndWritesKhrMaterialsSpecular) {
  json gltf = json::parse(readText(kGltfData / "triangle_spot.gltf"));
  gltf["materials"][0]["extensions"]["KHR_materials_specular"] = {
      {"specularFactor", 0.25}, {"specularColorFactor", {0.5, 1.0, 2.0}}};
  gltf["extensionsRequired"] = {"KHR_materials_specular"};
  TempDir dir;
  writeText(dir / "specular.gltf", gltf.dump());
  const engine::Scene scene = engine::loadGltf((dir / "specular.gltf").string());
  ASSERT_FALSE(scene.materials.empty());
  EXPECT_EQ(scene.materials[0].specularFactor, 0.25f);
  EXPECT_EQ(scene.materials[0].specularColorFactor, glm::vec3(0.5f, 1.0f, 2.0f));
  engine::writeGltf(scene, (dir / "back.gltf").string());
  const json written = json::parse(readText(dir / "back.gltf"));
  EXPECT_NE(std::find(written["extensionsUsed"].begin(), written["extensionsUsed"].end(),
                      "KHR_materials_specular"),
            written["extensionsUsed"].end());
  const engine::Scene back = engine::loadGltf((dir / "back.gltf").string());
  EXPECT_EQ(back.materials[0].specularFactor, 0.25f);
  EXPECT_EQ(back.materials[0].specularColorFactor, glm::vec3(0.5f, 1.0f, 2.0f));
  // Without the extension the defaults hold, and nothing is written.
  const engine::Scene plain = engine::loadGltf((kGltfData / "triangle_spot.gltf").string());
  EXPECT_EQ(plain.materials[0].specularFactor, 1.0f);
  engine::writeGltf(plain, (dir / "plain.gltf").string());
  EXPECT_EQ(readText(dir / "plain.gltf").find("KHR_materials_specular"), std::string::npos);
}

TEST(GltfWriter, RejectsInconsistentScenes) {
  engine::Scene scene = engine::loadGltf((kGltfData / "triangle_spot.gltf").string());
  scene.indices[2] = 7;
  TempDir dir;
  const fs::path path = dir / "bad.gltf";
  EXPECT_THROW(engine::writeGltf(scene, path.string()), engine::Error);
  EXPECT_FALSE(fs::exists(path));
}

TEST(GltfLoaderErrors, MissingFileAndWrongExtension) {
  expectLoadError(kGltfData / "no_such_file.gltf", "file not found");
  expectLoadError(kGltfData / "no_such_file.glb", "file not found");
  expectLoadError(kGltfData / "make_test_gltfs.py", "unsupported file extension '.py'");
}

TEST(GltfLoaderErrors, TruncatedAndMalformedJson) {
  TempDir dir;
  const std::string text = readText(kGltfData / "triangle_spot.gltf");
  writeText(dir / "truncated.gltf", text.substr(0, text.size() / 2));
  expectLoadError(dir / "truncated.gltf", "parse error");
  writeText(dir / "malformed.gltf", R"({"asset": {"version": "2.0"}, "nodes": [ }, ])");
  expectLoadError(dir / "malformed.gltf", "parse error");
  writeText(dir / "empty.gltf", "");
  expectLoadError(dir / "empty.gltf", "file is empty");
}

TEST(GltfLoaderErrors, TruncatedGlb) {
  TempDir dir;
  convertToGlb(kGltfData / "hierarchy.gltf", dir / "whole.glb");
  const std::vector<uint8_t> glb = readBytes(dir / "whole.glb");
  ASSERT_NO_THROW(engine::loadGltf((dir / "whole.glb").string()));
  writeBytes(dir / "half.glb", std::vector<uint8_t>(glb.begin(), glb.begin() + glb.size() / 2));
  expectLoadError(dir / "half.glb", "");
  writeBytes(dir / "header.glb", std::vector<uint8_t>(glb.begin(), glb.begin() + 10));
  expectLoadError(dir / "header.glb", "");
  // Every cut, each a clean error.
  for (size_t size = 0; size < glb.size(); size += 7) {
    SCOPED_TRACE(size);
    writeBytes(dir / "cut.glb",
               std::vector<uint8_t>(glb.begin(), glb.begin() + static_cast<long>(size)));
    expectLoadError(dir / "cut.glb", "");
  }
}

TEST(GltfLoaderErrors, BadBuffersAndIndices) {
  expectLoadError(kGltfData / "bad_short_buffer.gltf", "do not fit in bufferView");
  expectLoadError(kGltfData / "bad_index_out_of_range.gltf",
                  "index 5 at position 2 is out of range");
  expectLoadError(kGltfData / "bad_missing_buffer.gltf", "does_not_exist.bin");
}

TEST(GltfLoaderErrors, BadTextures) {
  expectLoadError(kGltfData / "bad_missing_texture.gltf", "does_not_exist.png");
  TempDir dir;
  std::string text = readText(kGltfData / "bad_missing_texture.gltf");
  text.replace(text.find("does_not_exist.png"), std::strlen("does_not_exist.png"), "garbage.png");
  writeText(dir / "undecodable.gltf", text);
  writeText(dir / "garbage.png", "this is not a PNG file at all");
  expectLoadError(dir / "undecodable.gltf", "garbage.png");
}

// A file without lights is a scene like any other: what lights it is the host's choice
// (samples/common/default_light.h for the sample programs).
TEST(GltfLoader, SceneWithoutLightsLoadsWithNone) {
  const engine::Scene scene = engine::loadGltf((kGltfData / "no_lights.gltf").string());
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_EQ(scene.triangleCount(), 1u);
}

TEST(GltfLoaderErrors, UnsupportedContent) {
  // Its one primitive is points, skipped: nothing is left to render.
  expectLoadError(kGltfData / "bad_points.gltf",
                  "scene has no triangles (" + (kGltfData / "bad_points.gltf").string() +
                      ": mesh 'triangle' primitive 0: skipped (points; only triangles are "
                      "rendered))");
  expectLoadError(kGltfData / "bad_spot_cone.gltf", "light 'badspot'");
  expectLoadError(kGltfData / "bad_spot_cone.gltf", "innerConeAngle");
}

// triangle_spot.gltf with its buffer in buf.bin beside it, `edit` applied to the JSON and
// `bytes` to the buffer, written to dir/name.
fs::path editedTriangle(const TempDir& dir, const std::string& name,
                        const std::function<void(json&)>& edit,
                        const std::function<void(std::vector<uint8_t>&)>& bytes = {}) {
  json g = json::parse(readText(kGltfData / "triangle_spot.gltf"));
  std::string uri = g["buffers"][0]["uri"];
  std::vector<uint8_t> buffer = base64Decode(uri.substr(uri.find(',') + 1));
  if (bytes) bytes(buffer);
  writeBytes(dir / "buf.bin", buffer);
  g["buffers"][0]["uri"] = "buf.bin";
  edit(g);
  writeText(dir / name, g.dump());
  return dir / name;
}

void putFloat(std::vector<uint8_t>& bytes, size_t offset, float value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(value));
}

// A lines primitive beside the triangles: the triangles load, the lines are named on one
// warning line, nothing else changes.
TEST(GltfLoader, LinesBesideTrianglesAreSkippedWithOneWarning) {
  TempDir dir;
  const fs::path path = editedTriangle(dir, "lines.gltf", [](json& g) {
    g["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 1}});
  });
  const engine::Scene scene = engine::loadGltf(path.string());
  EXPECT_EQ(scene.triangleCount(), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0],
            path.string() +
                ": mesh 'triangle' primitive 1: skipped (lines; only triangles are "
                "rendered)");
}

// An optional extension the loader does not implement is named once; a required one refuses
// the file with its name, before tinygltf (which would fail on its data with unrelated words).
TEST(GltfLoader, UnimplementedExtensionsAreNamed) {
  TempDir dir;
  const fs::path optional = editedTriangle(dir, "optional.gltf", [](json& g) {
    g["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_clearcoat"};
  });
  const engine::Scene scene = engine::loadGltf(optional.string());
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0], optional.string() +
                                   ": ignores extension 'KHR_materials_clearcoat' (the loader "
                                   "does not read it)");
  const fs::path basisu = editedTriangle(dir, "basisu.gltf", [](json& g) {
    g["extensionsUsed"] = {"KHR_texture_basisu"};
    g["extensionsRequired"] = {"KHR_texture_basisu"};
  });
  expectLoadError(basisu, "requires unsupported extension 'KHR_texture_basisu'");
}

// KHR_draco_mesh_compression (engine/src/gltf_draco.h): draco_grid.gltf, a 5 x 5 grid on a
// tilted plane compressed losslessly by draco_encoder (tests/data/gltf/make_test_gltfs.py),
// whose accessors have no bufferView. Draco's edgebreaker reorders points and faces, so the
// check is by position: every loaded corner lies on a grid vertex and carries that vertex's UV
// and the plane's normal, the winding agrees with the normal, and the area is the plane's.
TEST(GltfLoaderDraco, DecodesPositionsNormalsAndTextureCoordinates) {
  const engine::Scene scene = engine::loadGltf((kGltfData / "draco_grid.gltf").string());
  EXPECT_TRUE(scene.warnings.empty());
  ASSERT_EQ(scene.triangleCount(), 32u);
  const glm::vec3 normal = glm::normalize(glm::vec3(0.0f, 2.0f, 1.0f));
  double area = 0.0;
  for (uint32_t t = 0; t < scene.triangleCount(); ++t) {
    area += 0.5 * glm::length(glm::cross(corner(scene, t, 1) - corner(scene, t, 0),
                                         corner(scene, t, 2) - corner(scene, t, 0)));
    EXPECT_GT(glm::dot(geometricNormal(scene, t), normal), 0.9999f) << "triangle " << t;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = scene.indices[t * 3 + uint32_t(k)];
      const glm::vec3 p = scene.positions[v];
      // The grid vertex (x, y) sits at (x / 4, -y / 8, y / 4) with UV (x / 4, y / 4).
      const float x = std::round(p.x * 4.0f), y = std::round(p.z * 4.0f);
      expectVec3Near(p, {x / 4.0f, -y / 8.0f, y / 4.0f}, 1e-6f);
      expectVec3Near(scene.normals[v], normal, 1e-6f);
      EXPECT_NEAR(scene.uvs[v].x, x / 4.0f, 1e-6f);
      EXPECT_NEAR(scene.uvs[v].y, y / 4.0f, 1e-6f);
    }
  }
  EXPECT_NEAR(area, std::sqrt(1.25), 1e-5);  // 1 m x sqrt(1^2 + 0.5^2) m

  // The same file as a .glb (tinygltf parses it from memory with the edited JSON chunk).
  TempDir dir;
  convertToGlb(kGltfData / "draco_grid.gltf", dir / "draco_grid.glb");
  const engine::Scene binary = engine::loadGltf((dir / "draco_grid.glb").string());
  EXPECT_EQ(binary.indices, scene.indices);
  ASSERT_EQ(binary.positions.size(), scene.positions.size());
  for (size_t i = 0; i < scene.positions.size(); ++i)
    EXPECT_EQ(binary.positions[i], scene.positions[i]);
}

// EXT_meshopt_compression (engine/src/gltf_meshopt.h): the Draco test's 5 x 5 grid with its
// positions plain (mode ATTRIBUTES), its texture coordinates through the EXPONENTIAL filter and
// its indices as TRIANGLES, encoded by meshoptimizer here into compressed.bin. The views point
// at a fallback buffer without data, as a file that requires the extension may leave it.
struct MeshoptGrid {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
};

MeshoptGrid meshoptGrid() {
  MeshoptGrid g;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) {
      g.positions.push_back({float(x) / 4.0f, -float(y) / 8.0f, float(y) / 4.0f});
      g.uvs.push_back({float(x) / 4.0f, float(y) / 4.0f});
    }
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) {
      const uint32_t i = y * 5 + x;
      g.indices.insert(g.indices.end(), {i, i + 5, i + 1, i + 1, i + 5, i + 6});
    }
  return g;
}

// Writes meshopt.gltf and compressed.bin into `dir`; `edit` changes the JSON first.
fs::path writeMeshoptGltf(const TempDir& dir, const MeshoptGrid& g,
                          const std::function<void(json&)>& edit = {}) {
  std::vector<uint8_t> compressed;
  json views = json::array();
  size_t plainOffset = 0;
  const auto addView = [&](std::vector<uint8_t> bytes, size_t count, size_t stride,
                           const char* mode, const char* filter) {
    const size_t begin = compressed.size();
    compressed.insert(compressed.end(), bytes.begin(), bytes.end());
    while (compressed.size() % 4) compressed.push_back(0);
    json view = {{"buffer", 1}, {"byteOffset", plainOffset}, {"byteLength", count * stride}};
    if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
    view["extensions"]["EXT_meshopt_compression"] = {
        {"buffer", 0},          {"byteOffset", begin}, {"byteLength", bytes.size()},
        {"byteStride", stride}, {"count", count},      {"mode", mode},
        {"filter", filter}};
    views.push_back(view);
    plainOffset += count * stride;
  };
  const auto vertices = [](const void* data, size_t count, size_t stride) {
    std::vector<uint8_t> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
    return out;
  };
  std::vector<uint8_t> indices(
      meshopt_encodeIndexBufferBound(g.indices.size(), g.positions.size()));
  indices.resize(meshopt_encodeIndexBuffer(indices.data(), indices.size(), g.indices.data(),
                                           g.indices.size()));
  addView(indices, g.indices.size(), 4, "TRIANGLES", "NONE");
  addView(vertices(g.positions.data(), g.positions.size(), 12), g.positions.size(), 12,
          "ATTRIBUTES", "NONE");
  std::vector<uint32_t> exponential(g.uvs.size() * 2);
  meshopt_encodeFilterExp(exponential.data(), g.uvs.size(), 8, 24, &g.uvs[0].x);
  addView(vertices(exponential.data(), g.uvs.size(), 8), g.uvs.size(), 8, "ATTRIBUTES",
          "EXPONENTIAL");
  writeBytes(dir / "compressed.bin", compressed);
  json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"EXT_meshopt_compression"}},
      {"extensionsRequired", {"EXT_meshopt_compression"}},
      {"buffers",
       {{{"uri", "compressed.bin"}, {"byteLength", compressed.size()}},
        {{"byteLength", plainOffset},
         {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
      {"bufferViews", views},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5125},
         {"count", g.indices.size()},
         {"type", "SCALAR"}},
        {{"bufferView", 1},
         {"componentType", 5126},
         {"count", g.positions.size()},
         {"type", "VEC3"},
         {"min", {0.0, -0.5, 0.0}},
         {"max", {1.0, 0.0, 1.0}}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", g.uvs.size()}, {"type", "VEC2"}}}},
      {"meshes",
       {{{"name", "grid"},
         {"primitives",
          {{{"attributes", {{"POSITION", 1}, {"TEXCOORD_0", 2}}}, {"indices", 0}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  if (edit) edit(gltf);
  writeText(dir / "meshopt.gltf", gltf.dump());
  return dir / "meshopt.gltf";
}

// Each triangle rotated to start at its smallest index: the index codec may rotate triangles.
std::vector<uint32_t> canonicalTriangles(std::vector<uint32_t> indices) {
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    while (indices[t] > indices[t + 1] || indices[t] > indices[t + 2])
      std::rotate(indices.begin() + std::ptrdiff_t(t), indices.begin() + std::ptrdiff_t(t) + 1,
                  indices.begin() + std::ptrdiff_t(t) + 3);
  return indices;
}

TEST(GltfLoaderMeshopt, DecodesAttributesFiltersAndTriangles) {
  TempDir dir;
  const MeshoptGrid g = meshoptGrid();
  for (const bool binary : {false, true}) {
    SCOPED_TRACE(binary ? ".glb" : ".gltf");
    fs::path path = writeMeshoptGltf(dir, g);
    if (binary) {
      convertToGlb(path, dir / "meshopt.glb");
      path = dir / "meshopt.glb";
    }
    const engine::Scene scene = engine::loadGltf(path.string());
    EXPECT_TRUE(scene.warnings.empty());
    ASSERT_EQ(scene.positions.size(), g.positions.size());
    for (size_t i = 0; i < g.positions.size(); ++i) {
      EXPECT_EQ(scene.positions[i], g.positions[i]) << "vertex " << i;
      EXPECT_NEAR(scene.uvs[i].x, g.uvs[i].x, 1e-6f) << "vertex " << i;
      EXPECT_NEAR(scene.uvs[i].y, g.uvs[i].y, 1e-6f) << "vertex " << i;
    }
    EXPECT_EQ(canonicalTriangles(scene.indices), canonicalTriangles(g.indices));
  }
}

TEST(GltfLoaderMeshopt, BadViewsAreRefusedWithOneLine) {
  TempDir dir;
  const MeshoptGrid g = meshoptGrid();
  const auto ext = [](json& gltf, int view) -> json& {
    return gltf["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
  };
  expectLoadError(writeMeshoptGltf(dir, g, [&](json& j) { ext(j, 1)["byteLength"] = 5; }),
                  "bufferView 1: EXT_meshopt_compression data do not decode");
  expectLoadError(
      writeMeshoptGltf(dir, g, [&](json& j) { ext(j, 0)["byteStride"] = 8; }),
      "bufferView 0: EXT_meshopt_compression byteStride 8 does not suit mode TRIANGLES");
  expectLoadError(writeMeshoptGltf(dir, g, [&](json& j) { ext(j, 2)["count"] = 24; }),
                  "bufferView 2: EXT_meshopt_compression decodes 192 bytes, the view holds 200");
  expectLoadError(writeMeshoptGltf(dir, g, [&](json& j) { ext(j, 1).erase("mode"); }),
                  "bufferView 1: EXT_meshopt_compression mode '' is not ATTRIBUTES");
  expectLoadError(writeMeshoptGltf(dir, g, [&](json& j) { ext(j, 1)["filter"] = "OCTAHEDRAL"; }),
                  "bufferView 1: EXT_meshopt_compression filter 'OCTAHEDRAL' does not suit "
                  "byteStride 12");
}

// A Draco primitive whose data cannot be what its accessors say is refused with one line that
// names the file, the mesh and the primitive.
TEST(GltfLoaderDraco, BadDataIsRefusedWithOneLine) {
  TempDir dir;
  fs::copy_file(kGltfData / "draco_grid.drc", dir / "draco_grid.drc");
  const json original = json::parse(readText(kGltfData / "draco_grid.gltf"));
  const auto edited = [&](const std::string& name, const std::function<void(json&)>& edit) {
    json gltf = original;
    edit(gltf);
    writeText(dir / name, gltf.dump());
    return dir / name;
  };
  const auto draco = [](json& g) -> json& {
    return g["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
  };
  const std::string where = "mesh 'grid' primitive 0: ";
  expectLoadError(edited("half.gltf",
                         [](json& g) {
                           g["bufferViews"][0]["byteLength"] =
                               g["bufferViews"][0]["byteLength"].get<int>() / 2;
                         }),
                  where + "Draco data does not decode");
  expectLoadError(edited("id.gltf", [&](json& g) { draco(g)["attributes"]["NORMAL"] = 17; }),
                  where + "attribute id 17 is not in the Draco bitstream");
  expectLoadError(edited("count.gltf", [](json& g) { g["accessors"][3]["count"] = 24; }),
                  where + "accessor 3 has count 24, the Draco mesh 25 points");
  expectLoadError(edited("view.gltf", [&](json& g) { draco(g)["bufferView"] = 4; }),
                  where + "Draco bufferView 4 does not exist");
  expectLoadError(edited("name.gltf", [&](json& g) { draco(g)["attributes"]["COLOR_0"] = 3; }),
                  where + "Draco attribute 'COLOR_0' is not among the primitive's attributes");
}

// Deterministic corruption of the Draco bitstream and of the meshopt streams: every result must
// load or fail with engine::Error, never crash (run under VSGL_SANITIZE to catch silent overreads).
TEST(GltfLoaderErrors, CorruptedCompressedDataNeverCrashes) {
  TempDir dir;
  fs::copy_file(kGltfData / "draco_grid.gltf", dir / "draco_grid.gltf");
  const std::vector<uint8_t> draco = readBytes(kGltfData / "draco_grid.drc");
  writeMeshoptGltf(dir, meshoptGrid());
  const std::vector<uint8_t> meshopt = readBytes(dir / "compressed.bin");
  uint32_t state = 2026u;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  for (int i = 0; i < 200; ++i) {
    for (const auto& [bytes, file, gltf] :
         {std::tuple{&draco, "draco_grid.drc", "draco_grid.gltf"},
          std::tuple{&meshopt, "compressed.bin", "meshopt.gltf"}}) {
      std::vector<uint8_t> mutated = *bytes;
      for (int k = 0; k < 1 + i % 4; ++k)
        mutated[next() % mutated.size()] = static_cast<uint8_t>(next());
      writeBytes(dir / file, mutated);
      expectLoadsOrClean(dir / gltf);
    }
  }
}

TEST(GltfLoaderErrors, NonFiniteAttributesNameTheAccessor) {
  TempDir dir;
  auto none = [](json&) {};
  // Buffer layout: POSITION at 0, NORMAL at 36, TEXCOORD_0 at 72 (three vertices each).
  expectLoadError(editedTriangle(dir, "uv.gltf", none,
                                 [](std::vector<uint8_t>& b) { putFloat(b, 72, std::nanf("")); }),
                  "mesh 'triangle' primitive 0 TEXCOORD_0: non-finite texture coordinate at "
                  "vertex 0");
  expectLoadError(editedTriangle(dir, "normal.gltf", none,
                                 [](std::vector<uint8_t>& b) {
                                   putFloat(b, 36 + 12 + 4, std::numeric_limits<float>::infinity());
                                 }),
                  "mesh 'triangle' primitive 0 NORMAL: non-finite normal at vertex 1");
}

// What tinygltf would crash or hang on, or word as something else: each a one-line error.
TEST(GltfLoaderErrors, HostileFiles) {
  TempDir dir;
  // ~16 000 levels overflowed the stack inside tinygltf's parser (a 32 KB file).
  writeText(dir / "deep.gltf", R"({"asset": {"version": "2.0"}, "extras": )" +
                                   std::string(16000, '[') + std::string(16000, ']') + "}");
  expectLoadError(dir / "deep.gltf", "JSON nests deeper than 256 levels");
  // A buffer URI naming a FIFO blocked forever; one naming a directory read as bad_alloc.
  ASSERT_EQ(::mkfifo((dir / "fifo.bin").c_str(), 0600), 0);
  writeText(dir / "fifo.gltf",
            std::regex_replace(readText(editedTriangle(dir, "t.gltf", [](json&) {})),
                               std::regex("buf\\.bin"), "fifo.bin"));
  expectLoadError(dir / "fifo.gltf", "fifo.bin' is not a regular file");
  fs::create_directory(dir / "folder.bin");
  writeText(dir / "folder.gltf",
            std::regex_replace(readText(dir / "t.gltf"), std::regex("buf\\.bin"), "folder.bin"));
  expectLoadError(dir / "folder.gltf", "folder.bin' is a directory");
  // A URI is a path, never a shell word: tinygltf's default expanded it through wordexp.
  writeText(dir / "shell.gltf", std::regex_replace(readText(dir / "t.gltf"),
                                                   std::regex("buf\\.bin"), "$(touch pwned).bin"));
  expectLoadError(dir / "shell.gltf", "pwned");
  EXPECT_FALSE(fs::exists(dir / "pwned"));
  EXPECT_FALSE(fs::exists("pwned"));
  // Buffers declaring more than a scene may hold are refused before a byte of them is read.
  writeText(dir / "huge.gltf",
            std::regex_replace(readText(dir / "t.gltf"), std::regex("\"byteLength\":96"),
                               "\"byteLength\":3221225472"));
  expectLoadError(dir / "huge.gltf",
                  "its buffers hold 3072 MB, more than the 2048 MB a scene may use");
  // The file itself a directory.
  fs::create_directory(dir / "scene.gltf");
  expectLoadError(dir / "scene.gltf", "not a regular file");
}

TEST(GltfLoader, UpperCaseFileExtensions) {
  TempDir dir;
  fs::copy_file(kGltfData / "triangle_spot.gltf", dir / "TRIANGLE.GLTF");
  EXPECT_EQ(engine::loadGltf((dir / "TRIANGLE.GLTF").string()).triangleCount(), 1u);
  convertToGlb(kGltfData / "triangle_spot.gltf", dir / "TRIANGLE.GLB");
  EXPECT_EQ(engine::loadGltf((dir / "TRIANGLE.GLB").string()).triangleCount(), 1u);
}

// Edits of a valid file, each of which must be rejected with the given phrase.
TEST(GltfLoaderErrors, BadReferencesAndValues) {
  const json original = json::parse(readText(kGltfData / "triangle_spot.gltf"));
  struct Case {
    const char* name;
    std::function<void(json&)> edit;
    const char* phrase;
  };
  const Case cases[] = {
      {"mesh", [](json& g) { g["nodes"][0]["mesh"] = 7; }, "mesh 7 does not exist"},
      {"camera", [](json& g) { g["nodes"][2]["camera"] = 3; }, "camera 3 does not exist"},
      {"material", [](json& g) { g["meshes"][0]["primitives"][0]["material"] = 4; },
       "material 4 does not exist"},
      {"light", [](json& g) { g["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 9; },
       "light 9 does not exist"},
      {"node", [](json& g) { g["scenes"][0]["nodes"].push_back(12); }, "node 12 does not exist"},
      {"twice", [](json& g) { g["scenes"][0]["nodes"].push_back(0); }, "reached twice"},
      {"cycle", [](json& g) { g["nodes"][0]["children"] = {0}; }, "reached twice"},
      {"type", [](json& g) { g["accessors"][0]["type"] = "VEC2"; }, "expected type VEC3"},
      {"component", [](json& g) { g["accessors"][0]["componentType"] = 5121; },
       "unsupported componentType 5121"},
      {"stride", [](json& g) { g["bufferViews"][0]["byteStride"] = 8; }, "byteStride"},
      {"offset", [](json& g) { g["accessors"][0]["byteOffset"] = 4; }, "do not fit"},
      {"sparse",
       [](json& g) {
         g["accessors"][0]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", 0}, {"componentType", 5125}}},
                                        {"values", {{"bufferView", 0}}}};
       },
       "sparse accessors are not supported"},
      {"mode", [](json& g) { g["meshes"][0]["primitives"][0]["mode"] = 7; },
       "unknown primitive mode 7"},
      // Values tinygltf used to replace by their defaults without a word.
      {"base colour",
       [](json& g) {
         g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.5, 0.5};
       },
       "materials[0].pbrMetallicRoughness.baseColorFactor must be 4 numbers, got [0.5,0.5,0.5]"},
      {"negative offset", [](json& g) { g["accessors"][0]["byteOffset"] = -4; },
       "accessors[0].byteOffset must be a non-negative integer, got -4"},
      {"roughness",
       [](json& g) { g["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = 1.5; },
       "roughnessFactor must lie in [0, 1]"},
      {"texture",
       [](json& g) {
         g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 2}};
       },
       "texture 2 does not exist"},
      {"specular",
       [](json& g) {
         g["materials"][0]["extensions"]["KHR_materials_specular"] = {{"specularFactor", 1.5}};
       },
       "KHR_materials_specular specularFactor must be a number in [0, 1]"},
      {"specular colour",
       [](json& g) {
         g["materials"][0]["extensions"]["KHR_materials_specular"] = {
             {"specularColorFactor", {1.0, -0.5, 1.0}}};
       },
       "specularColorFactor values must be >= 0"},
      {"yfov", [](json& g) { g["cameras"][0]["perspective"]["yfov"] = 4.0; }, "yfov"},
      {"outer cone",
       [](json& g) {
         g["extensions"]["KHR_lights_punctual"]["lights"][0]["spot"]["outerConeAngle"] = 2.0;
       },
       "outerConeAngle"},
      {"no triangles", [](json& g) { g["nodes"][0].erase("mesh"); }, "scene has no triangles"},
      {"scene", [](json& g) { g["scene"] = 3; }, "scene 3 does not exist"},
      {"required extension", [](json& g) { g["extensionsRequired"] = {"KHR_texture_basisu"}; },
       "requires unsupported extension 'KHR_texture_basisu'"},
  };
  TempDir dir;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    json gltf = original;
    c.edit(gltf);
    const fs::path path = dir / (std::string("edit_") + std::to_string(&c - cases) + ".gltf");
    writeText(path, gltf.dump());
    expectLoadError(path, c.phrase);
  }
}

// Deterministic corruption of the JSON text and of the .glb bytes: every result must load or
// fail with engine::Error, never crash (run under VSGL_SANITIZE to catch silent overreads).
TEST(GltfLoaderErrors, CorruptedFilesNeverCrash) {
  TempDir dir;
  const std::string text = readText(kGltfData / "hierarchy.gltf");
  uint32_t state = 2024u;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  const char replacements[] = {'9', '0', '-', '"', '}', ']', ',', 'x', '5'};
  for (int i = 0; i < 150; ++i) {
    std::string mutated = text;
    mutated[next() % mutated.size()] = replacements[next() % sizeof(replacements)];
    writeText(dir / "mutated.gltf", mutated);
    expectLoadsOrClean(dir / "mutated.gltf");
  }
  convertToGlb(kGltfData / "textured.gltf", dir / "textured.glb");
  fs::copy_file(kGltfData / "checker2x2.png", dir / "checker2x2.png");
  const std::vector<uint8_t> glb = readBytes(dir / "textured.glb");
  for (int i = 0; i < 150; ++i) {
    std::vector<uint8_t> mutated = glb;
    mutated[next() % mutated.size()] = static_cast<uint8_t>(next());
    writeBytes(dir / "mutated.glb", mutated);
    expectLoadsOrClean(dir / "mutated.glb");
  }
}

}  // namespace
