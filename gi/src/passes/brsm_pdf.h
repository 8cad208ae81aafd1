// The view-dependent PDF over RSM texels (bidirectional RSM, Ritschel et al. 2011 in
// Tokuyoshi's two-stage form, vsgl-math.md section 7; formats in shaders/shared/brsm.h).
//   Stage A (ImportanceVsgls): the camera's G-buffer becomes importance VSGLs through the same
//     flux, attribute, mip and generation passes as a light's RSM, with unit emission and the
//     pixel's reflectance as its PDF ([S3] "additional G-buffer / mipmapping / filtered
//     sampling", upper row of Table 1).
//   Stage B (BrsmPdf): the importance VSGLs are evaluated at a grid of RSM cells and the product
//     with each texel's weights, mixed with the flux PDF, replaces the PDF channel of the
//     light's attribute pyramids, which are then mip-mapped again.
#pragma once

#include <string>

#include "gi/settings.h"
#include "passes/vsgl_generate.h"

namespace gi {

// Throws engine::Error naming the field when a setting is outside its range (rsmSize: the
// light's pyramid size).
void validateBrsmSettings(const BrsmSettings& settings, uint32_t rsmSize);

// Stage A. `width` x `height` is the camera G-buffer's size; the pyramids are the next power of
// two square (padding carries no power and no PDF). Pass names carry the prefix "brsm ".
class ImportanceVsgls {
 public:
  ImportanceVsgls(engine::Context& ctx, uint32_t width, uint32_t height, uint32_t maxCount);

  // `gbuffer`: the camera's G-buffer of the size given at construction, seen through `view`.
  // `settings.count` = BrsmSettings::importanceCount; [S3] uses K = 1 and the final VSGLs' rule.
  // `specular` = false: no surface has a specular lobe (VsglAttributes::record).
  // `broadReflections`: as VsglAttributes::record, for the receivers' glossy lobes.
  void record(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& view,
              const VsglSettings& settings, const MipPyramid& mips,
              engine::GpuProfiler* profiler = nullptr, bool specular = true,
              bool broadReflections = false);

  const engine::Buffer& vsgls() const { return generator_.vsgls(); }  // gpu::Vsgl[count]
  VsglAttributes& attributes() { return attributes_; }

 private:
  FluxPass flux_;
  VplImages vpls_;
  VsglAttributes attributes_;
  VsglGenerator generator_;
};

// Stage B over a light's attribute pyramids (already filled and mip-mapped).
class BrsmPdf {
 public:
  // `rsmSize`: the light pyramids' size; `gridSize` is fixed here (the cell pyramid's size).
  BrsmPdf(engine::Context& ctx, uint32_t rsmSize, uint32_t gridSize);

  // Evaluates the first `settings.importanceCount` records of `importance` at the cells, writes
  // the PDF into `light`'s diffuse axis pyramid and mip-maps it. `specular` false: the light's
  // and the importance VSGLs' specular lobes are all powerless (the planner's specularLobes), so
  // only I_d is evaluated and I_s is 0 (shaders/gi/brsm_evaluate.comp).
  void record(VkCommandBuffer cmd, VsglAttributes& light, const RsmView& view,
              const engine::Buffer& importance, const BrsmSettings& settings,
              const MipPyramid& mips, engine::GpuProfiler* profiler = nullptr,
              bool specular = true);

  engine::Image& cells() { return cells_; }  // the cell pyramid (shaders/shared/brsm.h)

 private:
  uint32_t rsmSize_;
  uint32_t gridSize_;
  engine::ComputeProgram evaluate_[2];  // brsm_evaluate.comp without, with specular lobes
  engine::ComputeProgram compose_;
  engine::Image cells_;
};

}  // namespace gi
