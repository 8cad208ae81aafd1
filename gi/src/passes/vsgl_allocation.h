// Sharing a frame's N VSGLs among the RSM views of its lights (shaders/shared/vsgl_allocation.h,
// docs/techniques/many-lights.md): after each view's attribute pyramids and PDF, recordWeight
// keeps the view's weights; recordAllocate then gives each view its range of the VSGL buffer,
// which VsglGenerator reads on the GPU. Nothing comes back to the host.
#pragma once

#include <vector>

#include "engine/profiler.h"
#include "engine/program.h"
#include "passes/vsgl_attributes.h"
#include "shared/vsgl_allocation.h"

namespace gi {

class VsglAllocation {
 public:
  explicit VsglAllocation(engine::Context& ctx);

  // The weights of view `view` (< VSGL_MAX_VIEWS) from its pyramids' top texels and, when
  // `cells` is given (the BRSM PDF's cell pyramid, filled for this view), its importance.
  void recordWeight(VkCommandBuffer cmd, uint32_t view, VsglAttributes& attributes,
                    engine::Image* cells);
  // The ranges of views [0, viewCount) for `count` VSGLs; fluxMix as the PDF mixes (1 = flux).
  void recordAllocate(VkCommandBuffer cmd, uint32_t viewCount, uint32_t count, float fluxMix,
                      engine::GpuProfiler* profiler = nullptr);
  // Ranges decided on the host (one view, or k-means' equal shares), written as they are.
  void recordRanges(VkCommandBuffer cmd, const std::vector<glm::uvec2>& ranges);

  engine::Buffer& weights() { return weights_; }            // gpu::VsglViewWeight[max views]
  const engine::Buffer& ranges() const { return ranges_; }  // gpu::VsglViewRange[max views]

 private:
  engine::ComputeProgram weight_, allocate_;
  engine::Buffer weights_, ranges_;
};

}  // namespace gi
