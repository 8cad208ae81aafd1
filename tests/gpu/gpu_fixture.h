// Base fixture of every GPU test: one Vulkan context with the Khronos validation layer for
// the whole test program. A test is skipped, with the reason, when no usable device exists,
// and fails when the validation layer reported anything while it ran.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "engine/direct_light.h"
#include "engine/gbuffer.h"
#include "engine/gbuffer_reference.h"
#include "engine/vk_context.h"

namespace testing_gpu {

// A camera frame with direct light only, read back: the decoded G-buffer and the radiance.
struct DirectFrame {
  engine::GBufferData gbuffer;
  std::vector<glm::vec4> radiance;  // RGBA32F, row 0 at the top
};

// One channel range of one pixel of a G-buffer material image set to a binary16 value: the
// non-finite material tests (vsgl-math.md section 12, case 14).
struct MaterialPoke {
  bool specular;  // the specular image (rgb F0) instead of the diffuse one (rgb albedo, a
                  // roughness)
  glm::uvec2 pixel;
  int first, last;  // channels first..last
  uint16_t bits;    // binary16, e.g. kHalfNan
};
constexpr uint16_t kHalfNan = 0x7E00, kHalfInf = 0x7C00;

class GpuTest : public ::testing::Test {
 protected:
  static engine::Context* context();  // nullptr when no device; see skipReason()
  static const std::string& skipReason();

  void SetUp() override;
  void TearDown() override;

  engine::Context& ctx() { return *context(); }

  // The camera G-buffer of `scene` seen through `view`, rasterised and resolved (blocking).
  engine::GBuffer renderGBuffer(const engine::SceneGpu& scene, const engine::View& view);
  // `scene` rasterised, resolved and lit by the direct-light pass (blocking).
  DirectFrame renderDirect(const engine::Scene& scene, const engine::View& view,
                           const engine::DirectLightSettings& settings);
  // Rewrites material channels of `gbuffer` in place (blocking); its images end in GENERAL.
  void pokeMaterials(engine::GBuffer& gbuffer, const std::vector<MaterialPoke>& pokes);

 private:
  uint32_t messagesBefore_ = 0;
};

}  // namespace testing_gpu
