#include "scene_files.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "engine/builtin_scenes.h"
#include "engine/environments.h"
#include "engine/error.h"
#include "engine/gltf.h"

namespace samples {

bool isBuiltinScene(const std::string& name) {
  auto names = engine::builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

engine::Scene loadScene(const std::string& name) {
  if (isBuiltinScene(name) || engine::isGeneratedSceneName(name))
    return engine::makeBuiltinScene(name);
  std::string extension = std::filesystem::path(name).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".gltf" && extension != ".glb")
    throw engine::Error("--scene: '" + name + "' is neither a built-in scene (" +
                        engine::builtinSceneList() +
                        ", or generated: sphere-room:N, sphere-room-outside:N) nor a .gltf/.glb "
                        "file");
  engine::Scene scene = engine::loadGltf(name);
  for (const std::string& warning : scene.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  return scene;
}

engine::ImageRgba32f loadEnvironment(const std::string& name, uint32_t builtinWidth) {
  const std::vector<std::string> builtins = engine::builtinEnvironmentNames();
  if (std::find(builtins.begin(), builtins.end(), name) != builtins.end())
    return engine::makeBuiltinEnvironment(name, builtinWidth);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(name, ec)) {
    std::string list;
    for (const std::string& b : builtins) list += (list.empty() ? "" : ", ") + b;
    throw engine::Error("--environment: '" + name + "' is neither a built-in environment (" + list +
                        ") nor an image file");
  }
  return engine::readImage(name);
}

void selectCamera(engine::Scene& scene, const std::string& choice) {
  if (choice.empty()) return;
  std::vector<engine::Camera>& cameras = scene.cameras;
  auto chosen = std::find_if(cameras.begin(), cameras.end(),
                             [&](const engine::Camera& c) { return c.name == choice; });
  if (chosen == cameras.end() &&
      std::all_of(choice.begin(), choice.end(), [](unsigned char c) { return std::isdigit(c); }) &&
      choice.size() < 10 && std::stoul(choice) < cameras.size())
    chosen = cameras.begin() + static_cast<std::ptrdiff_t>(std::stoul(choice));
  if (chosen == cameras.end()) {
    std::string list;
    for (size_t i = 0; i < cameras.size(); ++i)
      list += (i ? ", " : "") + std::to_string(i) + " '" + cameras[i].name + "'";
    throw engine::Error("--camera: '" + choice + "' is not a camera of " + scene.source +
                        (cameras.empty() ? " (it has none)" : " (cameras: " + list + ")"));
  }
  std::rotate(cameras.begin(), chosen, chosen + 1);
}

engine::View sceneView(const engine::Scene& scene, uint32_t width, uint32_t height) {
  const engine::Camera camera =
      scene.cameras.empty() ? engine::defaultCamera(scene) : scene.cameras.front();
  return engine::cameraView(camera, width, height);
}

void createOutputDirectory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw engine::Error(dir + ": cannot create output directory: " + ec.message());
}

void writePair(const std::string& base, const engine::ImageRgba32f& image,
               const engine::ToneMapSettings& toneMap) {
  engine::writeExr(base + ".exr", image);
  engine::writePng(base + ".png", image.width, image.height, engine::toneMap(image, toneMap));
}

}  // namespace samples
