// Recorded view paths (samples/common/view_path.h), which vsgl_viewer writes and vsgl_flicker
// replays: a path survives its file bit for bit (a replay must show the recorded frames, not
// ones a rounding away), the text has the documented layout, each kind of bad line is refused
// with one line naming the file, the line and the problem, and the checked-in
// tests/data/paths/orbit3.txt is what its comment here says it is.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <string>
#include <vector>

#include "engine/builtin_scenes.h"
#include "engine/error.h"
#include "view_path.h"

namespace {

using samples::PathFrame;

const std::string kHeader = "# vsgl view path v1\n";
const std::string kCamera = "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0.8 0 0.05 0 1 1\n";
const std::string kPoint = "light point 0 1 0 0 0 -1 1 1 1 5 0 0 0.7853982\n";

// A file of this test's own, so that tests run in parallel do not share one.
std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("vsgl_test_view_path_" + name + ".txt"))
      .string();
}

// The message parseViewPath throws for `text` read as "p.txt", or "" when it reads.
std::string errorOf(const std::string& text) {
  try {
    samples::parseViewPath(text, "p.txt");
  } catch (const engine::Error& e) {
    return e.what();
  }
  return "";
}

bool sameBits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

void expectSameCamera(const engine::Camera& a, const engine::Camera& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_TRUE(sameBits(a.cameraToWorld[c][r], b.cameraToWorld[c][r]))
          << "cameraToWorld[" << c << "][" << r << "]: " << a.cameraToWorld[c][r] << " vs "
          << b.cameraToWorld[c][r];
  EXPECT_EQ(a.perspective, b.perspective);
  EXPECT_TRUE(sameBits(a.yfov, b.yfov));
  EXPECT_TRUE(sameBits(a.aspectRatio, b.aspectRatio));
  EXPECT_TRUE(sameBits(a.znear, b.znear));
  EXPECT_TRUE(sameBits(a.zfar, b.zfar));
  EXPECT_TRUE(sameBits(a.xmag, b.xmag));
  EXPECT_TRUE(sameBits(a.ymag, b.ymag));
}

void expectSameLight(const engine::Light& a, const engine::Light& b) {
  EXPECT_EQ(a.type, b.type);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(sameBits(a.position[i], b.position[i])) << "position " << i;
    EXPECT_TRUE(sameBits(a.direction[i], b.direction[i])) << "direction " << i;
    EXPECT_TRUE(sameBits(a.color[i], b.color[i])) << "color " << i;
  }
  EXPECT_TRUE(sameBits(a.intensity, b.intensity));
  EXPECT_TRUE(sameBits(a.range, b.range));
  EXPECT_TRUE(sameBits(a.innerConeAngle, b.innerConeAngle));
  EXPECT_TRUE(sameBits(a.outerConeAngle, b.outerConeAngle));
}

// Two frames whose numbers have no short decimal form: a camera turned about an oblique axis,
// thirds, a subnormal, a negative zero; a spot, a point and a directional light, then an
// orthographic camera.
std::vector<PathFrame> awkwardFrames() {
  PathFrame a;
  a.camera.cameraToWorld =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, 1.7f, -2.3f)) *
      glm::rotate(glm::mat4(1.0f), 0.3f, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)));
  a.camera.yfov = 0.7f;
  a.camera.aspectRatio = 16.0f / 9.0f;
  a.camera.znear = 1.0f / 30.0f;
  a.camera.zfar = 0.0f;
  engine::Light spot;
  spot.type = engine::LightType::Spot;
  spot.position = {1.0f / 3.0f, 2.0f / 7.0f, -0.0f};
  spot.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.1f));
  spot.color = {1.0f, 0.9f, 0.8f};
  spot.intensity = 12.5f;
  spot.range = 1e-40f;  // subnormal
  spot.innerConeAngle = 0.35f;
  spot.outerConeAngle = 0.5f;
  engine::Light point;
  point.type = engine::LightType::Point;
  point.position = {-1.1f, 2.2f, 3.3f};
  point.color = {0.1f, 0.2f, 0.3f};
  point.intensity = 3.0e7f;
  point.range = 4.75f;
  engine::Light sun;
  sun.type = engine::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -0.8f, -0.5f));
  sun.intensity = 2.0f / 3.0f;
  a.lights = {spot, point, sun};

  PathFrame b;
  b.camera.cameraToWorld =
      glm::rotate(glm::mat4(1.0f), -1.234f, glm::vec3(0.0f, 1.0f, 0.0f)) * a.camera.cameraToWorld;
  b.camera.perspective = false;
  b.camera.znear = 0.0f;
  b.camera.zfar = 100.0f / 3.0f;
  b.camera.xmag = 2.5f;
  b.camera.ymag = 1.0f / 7.0f;
  b.lights = {point};
  return {a, b};
}

TEST(ViewPath, TwoFramesSurviveTheFileBitForBit) {
  const std::vector<PathFrame> frames = awkwardFrames();
  const std::string path = tempPath("round_trip");
  {
    samples::ViewPathWriter writer(path);
    for (const PathFrame& f : frames) writer.add(f);
    EXPECT_EQ(writer.frames(), 2u);
  }
  const std::vector<PathFrame> read = samples::readViewPath(path);
  ASSERT_EQ(read.size(), frames.size());
  for (size_t t = 0; t < frames.size(); ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    expectSameCamera(read[t].camera, frames[t].camera);
    EXPECT_EQ(read[t].camera.name, "");  // names are not recorded
    ASSERT_EQ(read[t].lights.size(), frames[t].lights.size());
    for (size_t i = 0; i < frames[t].lights.size(); ++i) {
      expectSameLight(read[t].lights[i], frames[t].lights[i]);
      EXPECT_EQ(read[t].lights[i].name, "");
    }
  }
  std::filesystem::remove(path);
}

TEST(ViewPath, TextHasTheDocumentedLayout) {
  PathFrame f;
  f.camera.yfov = 0.8f;
  engine::Light spot;
  spot.type = engine::LightType::Spot;
  spot.position = {0.5f, 1.0f, -2.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.color = {1.0f, 0.5f, 0.25f};
  spot.intensity = 12.0f;
  spot.innerConeAngle = 0.35f;
  spot.outerConeAngle = 0.5f;
  f.lights = {spot};
  EXPECT_EQ(samples::formatPathFrame(f, 7),
            "frame 7\n"
            "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0.8 0 0.05 0 1 1\n"
            "light spot 0.5 1 -2 0 -1 0 1 0.5 0.25 12 0 0.35 0.5\n");
  // The header, then the frames numbered as they were added.
  const std::string path = tempPath("layout");
  {
    samples::ViewPathWriter writer(path);
    writer.add(f);
    writer.add(f);
  }
  std::ifstream file(path);
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  EXPECT_EQ(text, kHeader + samples::formatPathFrame(f, 0) + samples::formatPathFrame(f, 1));
  std::filesystem::remove(path);
}

TEST(ViewPath, GoodTextReads) {
  const std::vector<PathFrame> frames =
      samples::parseViewPath(kHeader + "frame 0\n" + kCamera + kPoint + "\n" +  // a blank line
                                 "frame 1\r\n" + kCamera,  // CRLF, no final newline
                             "p.txt");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].lights.size(), 1u);
  EXPECT_EQ(frames[1].lights.size(), 0u);  // a frame may have no light (an environment's)
}

// Each bad line, with the line it is on.
TEST(ViewPath, EachProblemNamesItsLine) {
  const std::string f0 = "frame 0\n";
  const std::string spotZero = "light spot 0 1 0 0 0 0 1 1 1 5 0 0.2 0.5\n";
  const struct {
    std::string text, expect;
  } cases[] = {
      {"", "p.txt:1: missing header '# vsgl view path v1'"},
      {f0 + kCamera, "p.txt:1: missing header '# vsgl view path v1'"},
      {"# vsgl view path v2\n" + f0 + kCamera, "p.txt:1: missing header"},
      {kHeader + f0 + kCamera + "lamp 1 2 3\n",
       "p.txt:4: unknown line kind 'lamp' (frame, camera or light)"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0.8 0 0.05 0 1\n",
       "p.txt:3: camera: expected 23 numbers, got 22"},
      {kHeader + f0 + kCamera + "light point 0 1 0 0 0 -1 1 1 1 5 0 0\n",
       "p.txt:4: light: expected 13 numbers, got 12"},
      {kHeader + f0 + kCamera + "light\n", "p.txt:4: light: expected a type and 13 numbers"},
      {kHeader + "frame 0 1\n" + kCamera, "p.txt:2: frame: expected 1 number, got 2"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 inf 1 0.8 0 0.05 0 1 1\n",
       "p.txt:3: 'inf' is not a finite number"},
      {kHeader + f0 + kCamera + "light point 0 nan 0 0 0 -1 1 1 1 5 0 0 0.7\n",
       "p.txt:4: 'nan' is not a finite number"},
      {kHeader + f0 + kCamera + "light point 0 1 0 0 0 -1 1 1 1 5 0 0 0.7x\n",
       "p.txt:4: '0.7x' is not a number"},
      {kHeader + f0 + kCamera + "light point 0 1 0 0 0 -1 one 1 1 5 0 0 0.7\n",
       "p.txt:4: 'one' is not a number"},
      {kHeader + f0 + kCamera + "light point 0 1e39 0 0 0 -1 1 1 1 5 0 0 0.7\n",
       "p.txt:4: '1e39' is outside a float's range"},
      {kHeader + "frame 1\n" + kCamera, "p.txt:2: frame 1 where frame 0 was expected"},
      {kHeader + f0 + kCamera + "frame 2\n" + kCamera,
       "p.txt:4: frame 2 where frame 1 was expected"},
      {kHeader + f0 + kCamera + "frame 0\n" + kCamera,
       "p.txt:4: frame 0 where frame 1 was expected"},
      {kHeader + "frame -1\n" + kCamera, "p.txt:2: frame: '-1' is not a frame index"},
      {kHeader + kPoint + f0 + kCamera, "p.txt:2: light line before the first frame line"},
      {kHeader + "\n" + kCamera + f0 + kCamera, "p.txt:3: camera line before the first frame line"},
      {kHeader + f0 + kPoint + "frame 1\n" + kCamera, "p.txt:2: frame 0 has no camera line"},
      {kHeader + f0 + kCamera + "frame 1\n" + kPoint, "p.txt:4: frame 1 has no camera line"},
      {kHeader + f0 + kCamera + kCamera, "p.txt:4: frame 0 has a second camera line"},
      {kHeader + f0 + kCamera + spotZero, "p.txt:4: light: zero-length direction"},
      {kHeader + f0 + kCamera + "light directional 0 0 0 0 0 0 1 1 1 2 0 0 0.7\n",
       "p.txt:4: light: zero-length direction"},
      {kHeader, "p.txt:1: no frame"},
      {kHeader + "\n\n", "p.txt:3: no frame"},
      {kHeader + f0 + kCamera + "light area 0 1 0 0 0 -1 1 1 1 5 0 0 0.7\n",
       "p.txt:4: light: 'area' is not one of point, spot, directional"},
      // Values no frame can be rendered with (the glTF loader's rules).
      {kHeader + f0 + kCamera + "light point 0 1 0 0 0 -1 1 1 1 -5 0 0 0.7\n",
       "p.txt:4: light: intensity must be >= 0"},
      {kHeader + f0 + kCamera + "light point 0 1 0 0 0 -1 1 -1 1 5 0 0 0.7\n",
       "p.txt:4: light: color must be >= 0"},
      {kHeader + f0 + kCamera + "light point 0 1 0 0 0 -1 1 1 1 5 -1 0 0.7\n",
       "p.txt:4: light: range must be >= 0"},
      {kHeader + f0 + kCamera + "light spot 0 1 0 0 -1 0 1 1 1 5 0 0.5 0.5\n",
       "p.txt:4: light: spot cone angles must satisfy 0 <= inner < outer <= pi/2"},
      {kHeader + f0 + kCamera + "light spot 0 1 0 0 -1 0 1 1 1 5 0 0.5 1.6\n",
       "p.txt:4: light: spot cone angles"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 2 0.8 0 0.05 0 1 1\n",
       "p.txt:3: camera: perspective is '2', not 0 or 1"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0.8 0 0 0 1 1\n",
       "p.txt:3: camera: znear must be > 0"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 3.2 0 0.05 0 1 1\n",
       "p.txt:3: camera: yfov must be in (0, pi)"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0.8 0 0.05 0.01 1 1\n",
       "p.txt:3: camera: zfar must be > znear"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0.8 -1 0.05 0 1 1\n",
       "p.txt:3: camera: aspectRatio must be >= 0"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0 0.8 0 0 0 1 1\n",
       "p.txt:3: camera: an orthographic camera needs zfar > znear >= 0"},
      {kHeader + f0 + "camera 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0 0.8 0 0 10 0 1\n",
       "p.txt:3: camera: xmag and ymag must be > 0"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string message = errorOf(c.text);
    EXPECT_EQ(message.substr(0, c.expect.size()), c.expect) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ViewPath, MoreThan1000FramesAreRefused) {
  std::string text = kHeader;
  for (uint32_t t = 0; t < samples::kMaxPathFrames; ++t)
    text += "frame " + std::to_string(t) + "\n" + kCamera;
  EXPECT_EQ(samples::parseViewPath(text, "p.txt").size(), samples::kMaxPathFrames);
  text += "frame 1000\n" + kCamera;  // line 1 + 2 x 1000 + 1
  EXPECT_EQ(errorOf(text), "p.txt:2002: more than 1000 frames");

  // The writer refuses to write such a file.
  const std::string path = tempPath("too_long");
  samples::ViewPathWriter writer(path);
  for (uint32_t t = 0; t < samples::kMaxPathFrames; ++t) writer.add(PathFrame{});
  EXPECT_THROW(
      {
        try {
          writer.add(PathFrame{});
        } catch (const engine::Error& e) {
          EXPECT_EQ(std::string(e.what()), path + ": more than 1000 frames");
          throw;
        }
      },
      engine::Error);
  EXPECT_EQ(samples::readViewPath(path).size(), samples::kMaxPathFrames);
  std::filesystem::remove(path);
}

// A missing directory is made, as for every output of the sample programs; one that cannot be
// (its parent is a file) is named.
TEST(ViewPath, FilesThatCannotBeReadOrWrittenAreNamed) {
  const std::string directory = tempPath("missing_dir");
  std::filesystem::remove_all(directory);
  const std::string missing = directory + "/none.txt";
  try {
    samples::readViewPath(missing);
    ADD_FAILURE() << "read a missing file";
  } catch (const engine::Error& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": cannot read");
  }
  { samples::ViewPathWriter writer(missing); }
  EXPECT_TRUE(std::filesystem::is_regular_file(missing));
  const std::string blocked = missing + "/path.txt";  // under a file
  try {
    samples::ViewPathWriter writer(blocked);
    ADD_FAILURE() << "wrote under a file";
  } catch (const engine::Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing + ": cannot create output directory", 0), 0u)
        << e.what();
  }
  std::filesystem::remove_all(directory);
}

// tests/data/paths/orbit3.txt (vsgl_flicker's smoke test replays it): the built-in checker's
// camera turned -4, 0 and +4 degrees about the vertical axis through the scene's centre, each
// frame with the checker's spot. Written by ViewPathWriter from these frames; the unturned middle
// frame and the light must match bit for bit, the turned cameras to float rounding (the glm
// arithmetic may round differently under other compilers or flags).
TEST(ViewPath, Orbit3IsTheCheckerTurned) {
  const engine::Scene checker = engine::makeBuiltinScene("checker");
  const engine::Bounds b = checker.bounds();
  const glm::vec3 centre = 0.5f * (b.min + b.max);
  const std::vector<PathFrame> read =
      samples::readViewPath(std::string(VSGL_TEST_DATA) + "/paths/orbit3.txt");
  ASSERT_EQ(read.size(), 3u);
  for (uint32_t t = 0; t < 3; ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    engine::Camera expected = checker.cameras.at(0);
    if (t != 1) {
      const glm::mat4 turn =
          glm::translate(glm::mat4(1.0f), centre) *
          glm::rotate(glm::mat4(1.0f), glm::radians(4.0f * (float(t) - 1.0f)), glm::vec3(0, 1, 0)) *
          glm::translate(glm::mat4(1.0f), -centre);
      expected.cameraToWorld = turn * expected.cameraToWorld;
    }
    const engine::Camera& got = read[t].camera;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        EXPECT_NEAR(got.cameraToWorld[c][r], expected.cameraToWorld[c][r], 1e-6f);
    engine::Camera scalars = got;  // the matrix of the middle frame only is exact
    if (t != 1) scalars.cameraToWorld = expected.cameraToWorld;
    expectSameCamera(scalars, expected);
    ASSERT_EQ(read[t].lights.size(), checker.lights.size());
    for (size_t i = 0; i < checker.lights.size(); ++i)
      expectSameLight(read[t].lights[i], checker.lights[i]);
  }
  // The turn is real: 4 degrees between neighbouring frames' right vectors (horizontal, unlike
  // the view direction, which looks down at the floor).
  const glm::vec3 f0(read[0].camera.cameraToWorld[0]), f1(read[1].camera.cameraToWorld[0]);
  EXPECT_NEAR(glm::degrees(std::acos(glm::dot(f0, f1))), 4.0f, 0.01f);
}

}  // namespace
