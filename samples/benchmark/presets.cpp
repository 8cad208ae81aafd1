#include "presets.h"

#include "engine/error.h"

namespace bench {

const std::vector<std::string>& methods() {
  static const std::vector<std::string> names = {"tok15",
                                                 "modified",
                                                 "modified-full",
                                                 "modified-culled",
                                                 "modified-full-culled",
                                                 "modified-sg-emitter",
                                                 "modified-full-sg-emitter",
                                                 "kmeans-2d",
                                                 "kmeans-3d",
                                                 "vpl"};
  return names;
}

Preset preset(const std::string& name) {
  // Culling over full-rate shading is left to --methods: the presets time each method at every
  // N and K, and one culling variant shows its trade. The SG emitter (planar emitters off) runs
  // at full rate, where the two shade the same pixel-VSGL pairs: what the planar emitters cost
  // and buy.
  const std::vector<std::string> allMethods = {"tok15",
                                               "modified",
                                               "modified-full",
                                               "modified-culled",
                                               "modified-full-sg-emitter",
                                               "kmeans-2d",
                                               "kmeans-3d",
                                               "vpl"};
  const std::vector<std::string> allScenes = {"cornell", "checker", "atrium", "lounge"};
  if (name == "ci")  // one small scene: checks that every method runs and scores, not speed
    return {.name = "ci",
            .scenes = {"cornell"},
            .methods = allMethods,
            .counts = {16, 32},
            .kernelScales = {1.0f},
            .vplRsmSizes = {16},
            .width = 32,
            .height = 18,
            .rsmSize = 64,
            .importanceCount = 256,
            .warmup = 1,
            .frames = 2,
            .referenceNoise = 0.05f};
  // vsgl_render's defaults swept over N and K, at half its image size: on two cores the whole
  // sweep, references included, takes about 30 min instead of about 2 h. The VSGL stage does not
  // depend on the image size, and shading and the BRSM cost per pixel; --width 640 --height 360
  // gives the renderer's own size.
  if (name == "default")
    return {.name = "default",
            .scenes = allScenes,
            .methods = allMethods,
            .counts = {64, 128, 256, 512},
            .kernelScales = {1.0f, 4.0f},
            .vplRsmSizes = {32, 64, 128},  // 0.4-2 s, 1.4-9 s and 6-35 s per scene on 2 cores
            .width = 320,
            .height = 180,
            .rsmSize = 256,
            .importanceCount = 2048,
            .warmup = 1,
            .frames = 5,
            .referenceNoise = 0.03f};
  // [S3]'s setting: 1920x1088, RSM 512^2, 1024 VSGLs, 2048 importance VSGLs. No VPL gather
  // rows: at 2 M pixels even a 64^2 RSM is about 30 min of CPU rays.
  if (name == "paper")
    return {.name = "paper",
            .scenes = allScenes,
            .methods = allMethods,
            .counts = {1024},
            .kernelScales = {1.0f},
            .width = 1920,
            .height = 1088,
            .rsmSize = 512,
            .importanceCount = 2048,
            .warmup = 1,
            .frames = 3,
            .referenceNoise = 0.03f};
  throw engine::Error("--preset: '" + name + "' is not one of ci, default, paper");
}

}  // namespace bench
