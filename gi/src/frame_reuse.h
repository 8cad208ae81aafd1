// Reuse across frames (docs/techniques/reuse.md): what each stage of a frame reads. The module
// keeps each stage's inputs from the frame that last ran it; a stage whose inputs are equal in
// this frame keeps its outputs instead of recording its passes again. That is exact because
// each stage's outputs are written by that stage only, so they still hold what the same inputs
// produced, and every pass is deterministic (docs/flicker.md: a static capture is exactly 0).
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "gi/indirect_lighting.h"

namespace gi {

// The host's G-buffer and the camera that rendered it.
struct CameraInputs {
  uint64_t generation = 0;  // FrameInput::gbufferGeneration
  // The module's frame count when the generation is 0 (not known), else 0: an unknown
  // G-buffer then differs from that of every other frame.
  uint64_t unknownIn = 0;
  std::array<VkImageView, 4> views{};  // depth, normal, diffuse, specular
  DepthEncoding depthEncoding = DepthEncoding::Ndc;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  NormalEncoding normalEncoding = NormalEncoding::Octahedral;
  glm::mat4 view{1.0f}, proj{1.0f};
  bool operator==(const CameraInputs&) const = default;
};

// The geometry and materials.
struct SceneInputs {
  uint64_t serial = 0;      // setScene calls so far
  uint64_t generation = 0;  // FrameInput::sceneGeneration
  uint64_t unknownIn = 0;   // as CameraInputs::unknownIn
  bool operator==(const SceneInputs&) const = default;
};

CameraInputs cameraInputs(const FrameInput& in, uint64_t frame);
SceneInputs sceneInputs(uint64_t serial, const FrameInput& in, uint64_t frame);

// One RSM view: its RSM, flux and attribute pyramids. The view follows from the light, its
// face and the scene's bounds (part of the scene).
struct LightViewInputs {
  SceneInputs scene;
  Light light;
  uint32_t face = 0;  // a point light's cube face, else 0
  bool specularLobes = true;
  bool broadReflections = false;
  // The PDF channel of the pyramids is the flux PDF, or BRSM's, which the PDF pass writes over
  // it: pyramids kept from a BRSM frame cannot serve a flux-PDF one.
  PdfKind pdf = PdfKind::Brsm;
  bool operator==(const LightViewInputs&) const = default;
};

// BRSM stage A: the importance VSGLs of the camera's G-buffer.
struct ImportanceInputs {
  CameraInputs camera;
  uint32_t count = 0;
  KernelRule rule = KernelRule::Modified;
  bool specularLobes = true;
  bool broadReflections = false;
  bool operator==(const ImportanceInputs&) const = default;
};

// The VSGLs: every view's pyramids, the view importance and the generation's settings.
struct VsglInputs {
  std::vector<LightViewInputs> views;
  std::optional<ImportanceInputs> importance;
  uint32_t count = 0;
  float kernelScale = 0.0f;
  KernelRule rule = KernelRule::Modified;
  PdfKind pdf = PdfKind::Brsm;
  VsglMethod method = VsglMethod::FilteredImportanceSampling;
  KmeansSettings kmeans;
  BrsmSettings brsm;
  float surfaceTolerance = 0.0f;
  bool operator==(const VsglInputs&) const = default;
};

// The ISM point positions: the geometry, and the VSGL count that says which points are used.
struct IsmPositionInputs {
  SceneInputs scene;
  uint32_t vsglCount = 0;
  bool operator==(const IsmPositionInputs&) const = default;
};

// The imperfect shadow maps: the VSGLs they are seen from and the geometry they hold.
struct IsmInputs {
  VsglInputs vsgls;
  SceneInputs scene;
  bool operator==(const IsmInputs&) const = default;
};

// The outputs: the shading (or, without VSGLs, the black images) and the debug views. Every
// setting is compared: the plan's flags follow from them and the scene.
struct ShadingInputs {
  std::optional<VsglInputs> vsgls;  // none: the black outputs of a frame without a bounce
  bool isms = false;                // the ISMs were read
  CameraInputs camera;
  SceneInputs scene;
  Settings settings;
  bool operator==(const ShadingInputs&) const = default;
};

// The environment's outputs.
struct EnvironmentInputs {
  CameraInputs camera;
  uint64_t environment = 0;  // setEnvironment calls so far
  EnvironmentSettings settings;
  bool operator==(const EnvironmentInputs&) const = default;
};

// Each stage's inputs when it last ran (none: it never ran, or its outputs are not kept).
struct LastInputs {
  std::optional<SceneInputs> clusterBounds;  // the rasterizer's cluster boxes
  std::optional<CameraInputs> converted;
  std::optional<ImportanceInputs> importance;
  std::vector<std::optional<LightViewInputs>> views;  // by attribute pyramid
  std::optional<VsglInputs> vsgls;
  std::optional<IsmPositionInputs> ismPositions;
  std::optional<IsmInputs> isms;
  std::optional<ShadingInputs> shading;
  std::optional<EnvironmentInputs> environment;
};

}  // namespace gi
