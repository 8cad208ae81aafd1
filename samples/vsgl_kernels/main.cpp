// vsgl_kernels: the picture of [S3] Fig. 1 from the GPU passes. Renders the RSM of a built-in
// scene's first light, builds the VSGL attribute pyramids and the PDF (the view-dependent BRSM
// PDF from the scene camera's importance VSGLs, or the flux PDF), generates N VSGLs with the
// [T15] rule and with modified FIS ([S3] Eq. 3), and writes <out>/<scene>_kernels.png: the PDF
// in grey (left Tok15, right modified FIS) with each kernel's square in orange and its centre in
// red, as in the figure. Prints, per rule, how much PDF mass the kernels leave uncovered or
// cover more than once (gi/src/reference/fis_coverage.h), and the per-pass GPU times in the
// structure of [S3] Table 1.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli_values.h"
#include "engine/builtin_scenes.h"
#include "engine/error.h"
#include "engine/image_io.h"
#include "engine/scene_gpu.h"
#include "engine/view.h"
#include "gi_host.h"
#include "passes/brsm_pdf.h"
#include "program_exit.h"
#include "reference/fis_coverage.h"

namespace {

using engine::Error;

struct Options {
  std::string scene = "checker";
  std::string outDir = "out";
  uint32_t rsmSize = 128;
  uint32_t count = 256;      // N
  float kernelScale = 1.0f;  // K
  bool brsm = true;          // view-dependent PDF (else flux-proportional)
  gi::BrsmSettings brsmSettings;
  uint32_t width = 320;  // the BRSM's additional camera G-buffer
  uint32_t height = 180;
  uint32_t frames = 5;            // timed frames per rule (after one warm-up frame each)
  samples::CommonOptions common;  // --device, --validation, --help
};

const char* usage() {
  return "usage: vsgl_kernels [options]\n"
         "  --scene NAME   built-in scene (cornell, atrium, checker, lounge); its first spot or\n"
         "                 directional light (default checker)\n"
         "  --out DIR      output directory for <scene>_kernels.png (default out)\n"
         "  --rsm N        RSM texels per side, a power of two in 16..2048 (default 128)\n"
         "  --count N      VSGLs per rule, 1..65536 (default 256)\n"
         "  --frames N     timed frames per rule, alternating rules, 1..100 (default 5)\n"
         "  --k K          kernel scale K in [1, N]: kernels hold K/N of the PDF (default 1)\n"
         "  --pdf KIND     brsm (view-dependent, from the scene camera) or flux (default brsm)\n"
         "  --importance N importance VSGLs from the camera, 1..16384 (default 2048)\n"
         "  --brsm-grid N  cells per side of the BRSM evaluation, a power of two <= RSM (default "
         "32)\n"
         "  --flux-mix E   share of the flux PDF mixed into the BRSM PDF, (0, 1] (default 0.1)\n"
         "  --width W, --height H  the BRSM's camera G-buffer size (default 320x180)\n"
         "  --device SEL   Vulkan device index or name substring (default: VSGL_DEVICE or auto)\n"
         "  --validation   enable the Khronos validation layer (any message fails the run)\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  std::string_view kText = "1";  // as typed, for the range check once N is known
  for (samples::Arguments args(argc, argv); args.next();) {
    const std::string_view arg = args.option();
    if (arg == "--scene")
      o.scene = args.value();
    else if (arg == "--out")
      o.outDir = args.value();
    else if (arg == "--rsm")
      o.rsmSize = samples::parseUint(arg, args.value(), 16, 2048);
    else if (arg == "--count")
      o.count = samples::parseUint(arg, args.value(), 1, 65536);
    else if (arg == "--k")
      o.kernelScale = samples::parseFloat(arg, kText = args.value(), 1.0f, 65536.0f);
    else if (arg == "--frames")
      o.frames = samples::parseUint(arg, args.value(), 1, 100);
    else if (arg == "--pdf")
      o.brsm = samples::parseChoice<bool>(arg, args.value(), {{"brsm", true}, {"flux", false}});
    else if (arg == "--importance")
      o.brsmSettings.importanceCount =
          samples::parseUint(arg, args.value(), 1, gi::kMaxImportanceCount);
    else if (arg == "--brsm-grid")
      o.brsmSettings.gridSize = samples::parseUint(arg, args.value(), 1, 2048);
    else if (arg == "--flux-mix")
      o.brsmSettings.fluxMix = samples::parseFloat(arg, args.value(), 1e-6f, 1.0f);
    else if (arg == "--width")
      o.width = samples::parseUint(arg, args.value(), 16, 4096);
    else if (arg == "--height")
      o.height = samples::parseUint(arg, args.value(), 16, 4096);
    else
      samples::parseCommonOption(arg, args, o.common);
  }
  auto names = engine::builtinSceneNames();
  if (std::find(names.begin(), names.end(), o.scene) == names.end())
    throw Error("--scene: '" + o.scene + "' is not a built-in scene (" +
                engine::builtinSceneList() + ")");
  // The attribute pyramids and the 4^l / M of both rules need a power-of-two square.
  if (!std::has_single_bit(o.rsmSize))
    throw Error("--rsm: " + std::to_string(o.rsmSize) + " is not a power of two");
  if (!(o.kernelScale >= 1.0f && o.kernelScale <= float(o.count)))
    throw Error("--k: " + std::string(kText) + " is outside [1, N = " + std::to_string(o.count) +
                "]");
  if (o.outDir.empty()) throw Error("--out: empty path");
  if (!std::has_single_bit(o.brsmSettings.gridSize) || o.brsmSettings.gridSize > o.rsmSize)
    throw Error("--brsm-grid: " + std::to_string(o.brsmSettings.gridSize) +
                " is not a power of two <= the RSM size " + std::to_string(o.rsmSize));
  return o;
}

// 8-bit RGBA canvas for the two panels.
struct Canvas {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;

  Canvas(int w, int h) : width(w), height(h), rgba(size_t(w) * size_t(h) * 4, 255) {}
  void set(int x, int y, glm::u8vec3 c) {
    uint8_t* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
};

// [S3] Fig. 1's colours: orange kernels, red centres.
constexpr glm::u8vec3 kKernelColour{255, 150, 0};
constexpr glm::u8vec3 kCentreColour{235, 20, 20};
constexpr glm::u8vec3 kSeparatorColour{40, 90, 220};
constexpr int kSeparatorWidth = 4;
constexpr int kCentreRadius = 2;  // pixels
// The PDF is shown on a log scale over this many decades below its maximum (black below):
// the scenes' PDFs span several decades, and a linear or sqrt scale hides the dim regions
// where the [T15] kernels grow.
constexpr double kDecades = 3.0;

struct Panel {
  int x0 = 0;     // left pixel column on the canvas
  int size = 0;   // pixels per side
  int scale = 1;  // pixels per RSM texel
};

void drawPdf(Canvas& canvas, const Panel& panel, const std::vector<double>& pdf, uint32_t rsmSize) {
  const double largest = *std::max_element(pdf.begin(), pdf.end());
  for (int y = 0; y < panel.size; ++y)
    for (int x = 0; x < panel.size; ++x) {
      const double p = pdf[size_t(y / panel.scale) * rsmSize + size_t(x / panel.scale)];
      const double v = largest > 0.0 && p > 0.0
                           ? std::clamp(1.0 + std::log10(p / largest) / kDecades, 0.0, 1.0)
                           : 0.0;
      const auto g = uint8_t(std::lround(255.0 * v));
      canvas.set(panel.x0 + x, y, {g, g, g});
    }
}

// A kernel is the square of side 2^l texels centred at its centre (fis_coverage.h), drawn as a
// one-pixel outline clipped to the panel.
void drawKernel(Canvas& canvas, const Panel& panel, const glm::dvec3& kernel, uint32_t rsmSize) {
  const double pixels = double(panel.scale) * rsmSize;
  const double half = 0.5 * std::exp2(kernel.z) * panel.scale;
  const glm::dvec2 centre = glm::dvec2(kernel) * pixels;
  const int left = int(std::lround(centre.x - half)), top = int(std::lround(centre.y - half));
  const int right = std::max(left, int(std::lround(centre.x + half)) - 1);
  const int bottom = std::max(top, int(std::lround(centre.y + half)) - 1);
  auto plot = [&](int x, int y) {
    if (x >= 0 && x < panel.size && y >= 0 && y < panel.size)
      canvas.set(panel.x0 + x, y, kKernelColour);
  };
  for (int x = left; x <= right; ++x) plot(x, top), plot(x, bottom);
  for (int y = top; y <= bottom; ++y) plot(left, y), plot(right, y);
}

void drawCentre(Canvas& canvas, const Panel& panel, const glm::dvec3& kernel, uint32_t rsmSize) {
  const glm::dvec2 centre = glm::dvec2(kernel) * (double(panel.scale) * rsmSize);
  const int cx = int(std::floor(centre.x)), cy = int(std::floor(centre.y));
  for (int dy = -kCentreRadius; dy <= kCentreRadius; ++dy)
    for (int dx = -kCentreRadius; dx <= kCentreRadius; ++dx) {
      const int x = cx + dx, y = cy + dy;
      if (dx * dx + dy * dy <= kCentreRadius * kCentreRadius && x >= 0 && x < panel.size &&
          y >= 0 && y < panel.size)
        canvas.set(panel.x0 + x, y, kCentreColour);
    }
}

struct RuleRun {
  const char* name;
  uint32_t rule;
  std::vector<double> pdf;  // level 0 of the PDF this rule's frame warped
  std::vector<glm::dvec3> kernels;
};

// The BRSM's own resources: the additional camera G-buffer and both stages.
struct BrsmPasses {
  BrsmPasses(engine::Context& ctx, const Options& o)
      : gbuffer(engine::createGBuffer(ctx, o.width, o.height)),
        visibility(ctx, engine::Rasterizer::visibilityBytes(o.width, o.height),
                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly),
        importance(ctx, o.width, o.height, o.brsmSettings.importanceCount),
        pdf(ctx, o.rsmSize, o.brsmSettings.gridSize) {}

  engine::GBuffer gbuffer;
  engine::Buffer visibility;
  gi::ImportanceVsgls importance;
  gi::BrsmPdf pdf;
};

// Every pass of one frame of VSGL generation, from the camera G-buffer to the VSGL buffer.
class Frame {
 public:
  Frame(engine::Context& ctx, const Options& o, const engine::Scene& scene)
      : o_(o),
        scene_(engine::uploadScene(ctx, scene)),
        light_(scene.lights.at(size_t(samples::firstDirectedLight(scene)))),
        camera_(scene.cameras.at(0)),
        view_(gi::makeRsmView(scene, light_, o.rsmSize)),
        cameraView_(engine::cameraView(camera_, o.width, o.height)),
        rasterizer_(ctx),
        resolve_(ctx),
        mips_(ctx),
        rsm_(ctx, o.rsmSize),
        attributes_(ctx, o.rsmSize),
        generator_(ctx, o.count) {
    if (o.brsm) brsm_.emplace(ctx, o);
  }

  const engine::Light& light() const { return light_; }

  void record(VkCommandBuffer cmd, uint32_t rule, engine::GpuProfiler* profiler) {
    if (brsm_) {
      {
        // The BRSM's additional G-buffer (a host could hand in its own instead).
        engine::ProfileScope scope(profiler, cmd, "brsm camera g-buffer");
        rasterizer_.record(cmd, scene_, cameraView_.viewProj,
                           {&brsm_->visibility, 0, o_.width, o_.height});
        resolve_.record(cmd, scene_, brsm_->visibility, cameraView_, brsm_->gbuffer);
      }
      // The importance VSGLs use the rule under test, as in [S3] Table 1's BRSM row.
      brsm_->importance.record(cmd, brsm_->gbuffer, cameraView_,
                               {o_.brsmSettings.importanceCount, 1.0f, rule}, mips_, profiler);
    }
    rsm_.record(cmd, scene_, rasterizer_, resolve_, view_, light_, profiler);
    attributes_.record(cmd, rsm_.vpls(), rsm_.surface(), view_, mips_, profiler);
    if (brsm_)
      brsm_->pdf.record(cmd, attributes_, view_, brsm_->importance.vsgls(), o_.brsmSettings, mips_,
                        profiler);
    generator_.record(cmd, attributes_, view_, {o_.count, o_.kernelScale, rule}, profiler);
  }

  gi::VsglAttributes& attributes() { return attributes_; }
  const engine::Buffer& vsgls() const { return generator_.vsgls(); }

 private:
  const Options& o_;
  engine::SceneGpu scene_;
  engine::Light light_;
  engine::Camera camera_;
  gi::RsmView view_;
  engine::View cameraView_;
  engine::Rasterizer rasterizer_;
  engine::GBufferResolve resolve_;
  gi::MipPyramid mips_;
  gi::ReflectiveShadowMap rsm_;
  gi::VsglAttributes attributes_;
  gi::VsglGenerator generator_;
  std::optional<BrsmPasses> brsm_;  // only with --pdf brsm
};

// A row of the timing table and the profiler passes it adds up.
struct TimingRow {
  const char* label;
  std::vector<const char*> passes;
  bool counted;        // part of the VSGL generation total ([S3] Table 1 rows and BRSM evaluation)
  bool ruleDependent;  // the only rows whose work differs between the rules: filtered sampling
};

// GPU time per pass in the structure of [S3] Table 1: upper row the BRSM's importance VSGLs
// (additional G-buffer, mipmapping, filtered sampling), then the stage-B evaluation that the
// paper does not list, and the final row (additional RSM, mipmapping, filtered sampling). The
// RSM rasterisation is shown apart: the light's shadow map needs it anyway. The rules alternate
// frame by frame so that drift on a shared machine hits both alike. Every other pass records the
// same dispatches with the same amount of work under both rules, so its samples are pooled and
// one median serves both columns; otherwise the noise of those passes (up to 40 % frame to frame
// at the paper's setting) would swamp the rules' difference in the ratio.
void printTimings(engine::Context& ctx, const Options& o, Frame& frame) {
  std::vector<TimingRow> rows;
  if (o.brsm) {
    rows.push_back({"BRSM: additional G-buffer (raster)", {"brsm camera g-buffer"}, true, false});
    rows.push_back({"BRSM: additional G-buffer (flux, attributes)",
                    {"brsm camera flux", "brsm vsgl attributes"},
                    true,
                    false});
    rows.push_back({"BRSM: mipmapping", {"brsm attribute mipmapping"}, true, false});
    rows.push_back({"BRSM: filtered sampling", {"brsm filtered sampling"}, true, true});
    rows.push_back({"BRSM: evaluation at the RSM cells", {"brsm evaluation"}, true, false});
  }
  rows.push_back({"RSM rasterisation (the shadow map's)", {"rsm raster"}, false, false});
  rows.push_back({"final: additional RSM", {"rsm flux", "vsgl attributes"}, true, false});
  rows.push_back(
      {"final: mipmapping", {"attribute mipmapping", "brsm pdf mipmapping"}, true, false});
  rows.push_back({"final: filtered sampling", {"filtered sampling"}, true, true});

  std::map<std::string, std::vector<double>> times[2];
  engine::GpuProfiler profiler(ctx);
  for (uint32_t i = 0; i < 2 * (o.frames + 1); ++i) {
    const uint32_t rule = i % 2 ? VSGL_RULE_MODIFIED : VSGL_RULE_TOK15;
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      profiler.beginFrame(cmd);
      frame.record(cmd, rule, &profiler);
    });
    if (i < 2) continue;  // warm-up: pipelines compile at their first dispatch
    for (const auto& p : profiler.results()) times[rule][p.name].push_back(p.ms);
  }
  std::printf("GPU time per pass, median of %u frames per rule (ms)  Tok15   modified\n", o.frames);
  double total[2] = {0.0, 0.0}, sampling[2] = {0.0, 0.0};
  for (const TimingRow& row : rows) {
    double t[2] = {0.0, 0.0};
    for (const char* pass : row.passes) {
      if (row.ruleDependent) {
        for (int r = 0; r < 2; ++r) t[r] += engine::median(times[r][pass]);
      } else {
        std::vector<double> pooled = times[0][pass];
        pooled.insert(pooled.end(), times[1][pass].begin(), times[1][pass].end());
        t[0] = t[1] = t[0] + engine::median(pooled);
      }
    }
    std::printf("  %-46s %8.3f %8.3f%s\n", row.label, t[0], t[1],
                row.ruleDependent ? "" : "  (pooled)");
    for (int r = 0; r < 2; ++r) {
      if (row.counted) total[r] += t[r];
      if (row.ruleDependent) sampling[r] += t[r];
    }
  }
  std::printf("  %-46s %8.3f %8.3f  (modified / Tok15 = %.4f)\n", "VSGL generation total", total[0],
              total[1], total[1] / total[0]);
  std::printf("  %-46s %8.3f %8.3f  (modified / Tok15 = %.3f)\n", "filtered sampling only",
              sampling[0], sampling[1], sampling[1] / sampling[0]);
}

int run(const Options& o) {
  if (o.common.help) {
    std::printf("%s", usage());
    return 0;
  }
  std::error_code ec;
  std::filesystem::create_directories(o.outDir, ec);
  if (ec) throw Error(o.outDir + ": cannot create output directory: " + ec.message());

  engine::Scene scene = engine::makeBuiltinScene(o.scene);
  engine::Context ctx({o.common.validation, o.common.device});
  Frame frame(ctx, o, scene);
  std::printf("device: %s (%s)\nscene: %s, light '%s', RSM %u^2, N = %u, K = %g\n",
              ctx.info().name.c_str(), ctx.info().driver.c_str(), scene.source.c_str(),
              frame.light().name.c_str(), o.rsmSize, o.count, double(o.kernelScale));
  if (o.brsm)
    std::printf(
        "PDF: BRSM, %u importance VSGLs from a %ux%u camera G-buffer, %u^2 cells, flux "
        "mix %g\n",
        o.brsmSettings.importanceCount, o.width, o.height, o.brsmSettings.gridSize,
        double(o.brsmSettings.fluxMix));
  else
    std::printf("PDF: flux-proportional\n");

  std::vector<RuleRun> runs{{"Tok15 [T15]", VSGL_RULE_TOK15, {}, {}},
                            {"modified FIS [S3]", VSGL_RULE_MODIFIED, {}, {}}};
  for (RuleRun& r : runs) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) { frame.record(cmd, r.rule, nullptr); });
    // The PDF the generator warped: alpha of the diffuse-axis pyramid (vsgl_attributes.h). With
    // the BRSM it differs between the rules, whose importance VSGLs differ.
    for (const glm::vec4& t :
         frame.attributes().pyramid(VSGL_ATTR_DIFFUSE_AXIS).readbackRgba32f(ctx, 0))
      r.pdf.push_back(t.w);
    const auto vsgls = frame.vsgls().readbackAs<gpu::Vsgl>(ctx);
    for (uint32_t i = 0; i < o.count; ++i) r.kernels.emplace_back(glm::dvec3(vsgls[i].kernel));
  }
  for (const RuleRun& r : runs) {
    const gi::KernelCoverage c =
        gi::measureCoverage(gi::makeScalarPyramid(r.pdf, o.rsmSize), r.kernels);
    std::printf("%-18s PDF mass uncovered %6.2f %%, covered twice or more %6.2f %%, sum %6.2f %%\n",
                r.name, 100.0 * c.uncoveredMass, 100.0 * c.multiplyCoveredMass,
                100.0 * (c.uncoveredMass + c.multiplyCoveredMass));
  }

  // An integer upscale keeps texels square and at least 512 pixels per panel.
  const int scale = int(std::max(1u, 512u / o.rsmSize));
  const int panelSize = scale * int(o.rsmSize);
  Canvas canvas(2 * panelSize + kSeparatorWidth, panelSize);
  for (int y = 0; y < canvas.height; ++y)
    for (int x = 0; x < kSeparatorWidth; ++x) canvas.set(panelSize + x, y, kSeparatorColour);
  for (size_t i = 0; i < runs.size(); ++i) {
    const Panel panel{int(i) * (panelSize + kSeparatorWidth), panelSize, scale};
    drawPdf(canvas, panel, runs[i].pdf, o.rsmSize);
    // Centres on top of every square, so that none hides under a neighbour's outline.
    for (const glm::dvec3& k : runs[i].kernels) drawKernel(canvas, panel, k, o.rsmSize);
    for (const glm::dvec3& k : runs[i].kernels) drawCentre(canvas, panel, k, o.rsmSize);
  }
  printTimings(ctx, o, frame);

  const std::string path = (std::filesystem::path(o.outDir) / (o.scene + "_kernels.png")).string();
  engine::writePng(path, canvas.width, canvas.height, canvas.rgba);
  std::printf(
      "wrote %s (left Tok15, right modified FIS; PDF on a %g-decade log scale, %dx upscale)\n",
      path.c_str(), kDecades, scale);
  return samples::validationExitStatus(ctx, "vsgl_kernels");
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_kernels", [&] { return run(parseOptions(argc, argv)); });
}
