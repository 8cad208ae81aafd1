// The benchmark's presets (docs/benchmarks.md): which scenes, methods, VSGL counts and kernel
// scales it runs, at what size, and how converged the path-traced reference is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct Preset {
  std::string name;
  std::vector<std::string> scenes;
  // Names of methods(): vsgl_render's --method names and variants of modified FIS
  std::vector<std::string> methods;
  std::vector<uint32_t> counts;     // VSGLs N
  std::vector<float> kernelScales;  // K (filtered methods only; k-means has none)
  // RSM sides of the brute-force VPL gather rows (gi/truth, on the CPU: a row costs pixels x
  // RSM texels visibility rays, so the sizes stay small); empty = no such rows.
  std::vector<uint32_t> vplRsmSizes;
  uint32_t width = 0, height = 0;
  uint32_t rsmSize = 0;
  uint32_t importanceCount = 0;  // BRSM importance VSGLs
  uint32_t warmup = 1, frames = 3;
  // The path tracer's relative standard-error target. A float, as vsgl_reference parses it, so
  // both programs key the same reference in a shared cache.
  float referenceNoise = 0.03f;
};

// Every method a row can run: vsgl_render's --method names (tok15, modified, kmeans-2d,
// kmeans-3d, vpl) and variants of modified FIS: modified-full (adaptive shading off, every pixel
// shaded), modified-culled and modified-full-culled (VSGL culling on), modified-sg-emitter and
// modified-full-sg-emitter (planar emitters off: the SG emitter for every VSGL).
const std::vector<std::string>& methods();

// "ci" (a smoke run, well under 2 minutes), "default" or "paper"; throws engine::Error naming
// the known presets otherwise.
Preset preset(const std::string& name);

}  // namespace bench
