#include "presets.h"

#include "engine/error.h"

namespace bench {

Preset preset(const std::string& name) {
  const std::vector<std::string> allMethods = {"tok15", "modified", "kmeans-2d", "kmeans-3d"};
  const std::vector<std::string> allScenes = {"cornell", "checker", "atrium"};
  if (name == "ci")  // one small scene: checks that every method runs and scores, not speed
    return {"ci", {"cornell"}, allMethods, {16, 32}, {1.0f}, 32, 18, 64, 256, 1, 2, 0.05};
  if (name == "default")  // vsgl_render's defaults, swept over N and K
    return {"default",    allScenes, allMethods, {64, 128, 256, 512},
            {1.0f, 4.0f}, 640,       360,        256,
            2048,         1,         3,          0.03};
  if (name == "paper")  // [S3]'s setting: 1920x1088, RSM 512^2, 1024 VSGLs, 2048 importance
    return {"paper", allScenes, allMethods, {1024}, {1.0f}, 1920, 1088, 512, 2048, 1, 3, 0.03};
  throw engine::Error("--preset: '" + name + "' is not one of ci, default, paper");
}

}  // namespace bench
