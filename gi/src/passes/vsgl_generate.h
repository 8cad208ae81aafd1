// VSGL generation by filtered importance sampling ("filtered sampling" in [S3] Table 1): one
// dispatch of vsgl_generate.comp over the attribute pyramids writes N gpu::Vsgl records.
#pragma once

#include "passes/vsgl_attributes.h"
#include "shared/vsgl.h"

namespace gi {

struct VsglSettings {
  uint32_t count = 1024;     // N, [1, maxCount] VSGLs; cost ~ N (generation and shading)
  float kernelScale = 1.0f;  // K, [1, N]: kernels hold K/N of the PDF; larger = blurrier
                             // and temporally steadier (paper: 1)
  // VSGL_RULE_TOK15, VSGL_RULE_MODIFIED (+~0 cost) or VSGL_RULE_POINT (the VPL baseline's
  // point lights; K is not read)
  uint32_t rule = VSGL_RULE_MODIFIED;
  // The record index of the first VSGL written: the views of a point light write their VSGLs
  // one after another into the same buffer. first + count <= maxCount.
  uint32_t first = 0;
  // > 0: kernels that leave their surface are shrunk (VsglGeneratePush::surfaceTolerance);
  // VSGL_RULE_POINT reads one texel and ignores it.
  float surfaceTolerance = 0.0f;
};

class VsglGenerator {
 public:
  // `passPrefix` is put before the profiler's pass name, "filtered sampling" ("vpl sampling"
  // for VSGL_RULE_POINT).
  VsglGenerator(engine::Context& ctx, uint32_t maxCount, std::string passPrefix = {});

  void record(VkCommandBuffer cmd, VsglAttributes& attributes, const RsmView& view,
              const VsglSettings& settings, engine::GpuProfiler* profiler = nullptr);
  // The same with this view's first record and count read on the GPU from `ranges`
  // (gpu::VsglViewRange[], VsglAllocation) at `rangeIndex`; settings.count (the frame's N)
  // bounds the count, settings.first is not read.
  void recordRanged(VkCommandBuffer cmd, VsglAttributes& attributes, const RsmView& view,
                    const VsglSettings& settings, const engine::Buffer& ranges, uint32_t rangeIndex,
                    engine::GpuProfiler* profiler = nullptr);

  const engine::Buffer& vsgls() const { return vsgls_; }  // gpu::Vsgl[maxCount]

 private:
  void dispatch(VkCommandBuffer cmd, VsglAttributes& attributes, const RsmView& view,
                const VsglSettings& settings, const engine::Buffer* ranges, uint32_t rangeIndex,
                engine::GpuProfiler* profiler);

  uint32_t maxCount_;
  std::string passPrefix_;
  engine::ComputeProgram program_;
  engine::Sampler sampler_;  // unused by texelFetch, but a combined image sampler needs one
  engine::Buffer vsgls_;
  engine::Buffer noRanges_;  // bound when the count is the push constant's (never read)
};

}  // namespace gi
