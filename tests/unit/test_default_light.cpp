// The sample programs' --light rules (samples/common/default_light.h): what lights a scene
// whose file has no light, and what replaces the file's lights.
#include <gtest/gtest.h>

#include <cmath>

#include "default_light.h"
#include "engine/builtin_scenes.h"
#include "engine/error.h"
#include "engine/gltf.h"

namespace {

const std::string kNoLights = std::string(VSGL_TEST_DATA) + "/gltf/no_lights.gltf";

glm::vec3 forwardOf(const engine::Scene& scene) {
  const engine::Camera c =
      scene.cameras.empty() ? engine::defaultCamera(scene) : scene.cameras.front();
  return glm::normalize(-glm::vec3(c.cameraToWorld[2]));
}

TEST(DefaultLight, AutoAddsTheSunOnlyToAFileWithoutLights) {
  engine::Scene bare = engine::loadGltf(kNoLights);
  ASSERT_TRUE(bare.lights.empty());
  const std::string note = samples::applyLightChoice(bare, samples::LightChoice::Auto, false, 1.0f);
  ASSERT_EQ(bare.lights.size(), 1u);
  EXPECT_EQ(bare.lights[0].type, engine::LightType::Directional);
  EXPECT_EQ(note.rfind("light: " + kNoLights + " has no light; added the default sun", 0), 0u)
      << note;

  engine::Scene lit = engine::makeBuiltinScene("cornell");
  const engine::Light own = lit.lights.at(0);
  EXPECT_EQ(samples::applyLightChoice(lit, samples::LightChoice::Auto, false, 1.0f), "");
  ASSERT_EQ(lit.lights.size(), 1u);
  EXPECT_EQ(lit.lights[0].name, own.name);

  // An environment lights the scene: auto adds nothing then.
  engine::Scene withEnvironment = engine::loadGltf(kNoLights);
  EXPECT_EQ(samples::applyLightChoice(withEnvironment, samples::LightChoice::Auto, true, 1.0f), "");
  EXPECT_TRUE(withEnvironment.lights.empty());
}

TEST(DefaultLight, NoneRefusesAnUnlitFileWithTheFix) {
  engine::Scene bare = engine::loadGltf(kNoLights);
  try {
    samples::applyLightChoice(bare, samples::LightChoice::None, false, 1.0f);
    FAIL() << "an unlit scene without an environment must be refused";
  } catch (const engine::Error& e) {
    EXPECT_EQ(std::string(e.what()),
              kNoLights +
                  ": no light (KHR_lights_punctual) and no --environment to render by; "
                  "use --light auto, sun or headlight, or --environment");
  }
  EXPECT_EQ(samples::applyLightChoice(bare, samples::LightChoice::None, true, 1.0f), "");
  EXPECT_TRUE(bare.lights.empty());
}

// The sun's rule: 50 degrees above the horizon, travelling along the camera's horizontal forward
// turned 45 degrees to its right, so it lights what the camera faces; it replaces the file's
// lights with --light sun.
TEST(DefaultLight, SunComesFromAboveOverTheCamerasLeftShoulder) {
  for (const std::string& name : engine::builtinSceneNames()) {
    SCOPED_TRACE(name);
    engine::Scene scene = engine::makeBuiltinScene(name);
    samples::applyLightChoice(scene, samples::LightChoice::Sun, false, 16.0f / 9.0f);
    ASSERT_EQ(scene.lights.size(), 1u);
    const engine::Light& sun = scene.lights[0];
    EXPECT_EQ(sun.type, engine::LightType::Directional);
    EXPECT_FLOAT_EQ(sun.intensity, samples::kDefaultIlluminance);
    EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-6f);
    EXPECT_NEAR(std::asin(-sun.direction.y), 50.0 * M_PI / 180.0, 1e-5);
    const glm::vec3 f = forwardOf(scene);
    const glm::vec3 horizontal = glm::normalize(glm::vec3(f.x, 0.0f, f.z));
    const glm::vec3 travel = glm::normalize(glm::vec3(sun.direction.x, 0.0f, sun.direction.z));
    EXPECT_NEAR(glm::dot(travel, horizontal), std::cos(M_PI / 4.0), 1e-5) << "45 degrees off";
    const glm::vec3 right = glm::cross(horizontal, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_GT(glm::dot(travel, right), 0.0f) << "turned to the camera's right";
  }
}

// The headlight sits at the eye, looks along the view, reaches the image's corners and gives
// the scene's centre kDefaultIlluminance at normal incidence.
TEST(DefaultLight, HeadlightCoversTheImageFromTheEye) {
  engine::Scene scene = engine::makeBuiltinScene("atrium");
  const engine::Camera camera = scene.cameras.front();
  const engine::Bounds b = scene.bounds();
  const float aspect = 16.0f / 9.0f;
  samples::applyLightChoice(scene, samples::LightChoice::Headlight, false, aspect);
  ASSERT_EQ(scene.lights.size(), 1u);
  const engine::Light& spot = scene.lights[0];
  EXPECT_EQ(spot.type, engine::LightType::Spot);
  EXPECT_EQ(spot.position, glm::vec3(camera.cameraToWorld[3]));
  EXPECT_NEAR(glm::dot(spot.direction, forwardOf(scene)), 1.0f, 1e-6f);
  const float corner = std::atan(std::tan(0.5f * camera.yfov) * std::sqrt(1.0f + aspect * aspect));
  EXPECT_GT(spot.outerConeAngle, corner);
  EXPECT_LE(spot.outerConeAngle, 1.2f);
  EXPECT_LT(spot.innerConeAngle, spot.outerConeAngle);
  const float d = glm::length(0.5f * (b.min + b.max) - spot.position);
  EXPECT_NEAR(spot.intensity / (d * d), samples::kDefaultIlluminance, 1e-4f);
}

TEST(DefaultLight, ChoiceParsingNamesTheAcceptedWords) {
  EXPECT_EQ(samples::parseLightChoice("--light", "headlight"), samples::LightChoice::Headlight);
  try {
    samples::parseLightChoice("--light", "lamp");
    FAIL();
  } catch (const engine::Error& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("--light: 'lamp' is not one of auto, sun, headlight, none", 0),
        0u)
        << e.what();
  }
}

}  // namespace
