// What the sample programs share about scenes and pictures: the --scene argument (a built-in
// scene's name or a glTF file), the output directory, and the EXR + PNG pair written for every
// picture.
#pragma once

#include <cstdint>
#include <string>

#include "engine/image_io.h"
#include "engine/scene.h"
#include "engine/tonemap.h"
#include "engine/view.h"

namespace samples {

bool isBuiltinScene(const std::string& name);
// Throws engine::Error("--scene: ...") for anything that is neither. A file's load warnings
// (Scene::warnings) go to stderr, one "warning: " line each.
engine::Scene loadScene(const std::string& name);
// The --environment argument: a built-in environment's name (engine/environments.h, made
// builtinWidth x builtinWidth / 2) or an equirectangular image file OpenImageIO reads (HDR, EXR,
// ...), y up. Throws engine::Error naming the argument or the file.
engine::ImageRgba32f loadEnvironment(const std::string& name, uint32_t builtinWidth = 1024);
// --camera NAME|INDEX: moves that camera of `scene` to the front, where sceneView, the default
// lights and every program look ("" keeps the first). A name is matched first, then an index.
// Throws engine::Error naming the choice and listing the scene's cameras when none matches.
void selectCamera(engine::Scene& scene, const std::string& choice);
#define SAMPLES_CAMERA_USAGE                                                          \
  "  --camera NAME|INDEX  the file's camera to look through (default: its first; a\n" \
  "                       file without cameras gets a framing of the whole scene)\n"
// The scene's first camera (or the default framing) for a width x height image.
engine::View sceneView(const engine::Scene& scene, uint32_t width, uint32_t height);
// Creates `dir` (and parents); throws engine::Error naming it on failure.
void createOutputDirectory(const std::string& dir);
// A width x height linear image whose pixel i is value(i) (a glm::dvec3), alpha 1.
template <class F>
engine::ImageRgba32f imageFrom(uint32_t width, uint32_t height, F value) {
  engine::ImageRgba32f image{int(width), int(height), {}};
  image.pixels.reserve(size_t{width} * height * 4);
  for (size_t i = 0; i < size_t{width} * height; ++i) {
    const glm::dvec3 v = value(i);
    for (int k = 0; k < 3; ++k) image.pixels.push_back(static_cast<float>(v[k]));
    image.pixels.push_back(1.0f);
  }
  return image;
}

// <base>.exr (linear) and <base>.png (tone-mapped sRGB).
void writePair(const std::string& base, const engine::ImageRgba32f& image,
               const engine::ToneMapSettings& toneMap);

}  // namespace samples
