// vsgl_kernels: the picture of [S3] Fig. 1 from the GPU passes. Renders the RSM of a built-in
// scene's first light, builds the VSGL attribute pyramids, generates N VSGLs with the [T15] rule
// and with modified FIS ([S3] Eq. 3), and writes <out>/<scene>_kernels.png: the PDF in grey
// (left Tok15, right modified FIS) with each kernel's square in orange and its centre in red, as
// in the figure. Prints, per rule, how much PDF mass the kernels leave uncovered or cover more
// than once (gi/src/reference/fis_coverage.h).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "cli_values.h"
#include "engine/builtin_scenes.h"
#include "engine/error.h"
#include "engine/image_io.h"
#include "engine/scene_gpu.h"
#include "passes/vsgl_attributes.h"
#include "passes/vsgl_generate.h"
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
  uint32_t frames = 5;       // timed frames per rule (after one warm-up frame each)
  std::string device;
  bool validation = false;
  bool help = false;
};

const char* usage() {
  return "usage: vsgl_kernels [options]\n"
         "  --scene NAME   built-in scene (cornell, atrium, checker); its first light (default "
         "checker)\n"
         "  --out DIR      output directory for <scene>_kernels.png (default out)\n"
         "  --rsm N        RSM texels per side, a power of two in 16..2048 (default 128)\n"
         "  --count N      VSGLs per rule, 1..65536 (default 256)\n"
         "  --frames N     timed frames per rule, alternating rules, 1..100 (default 5)\n"
         "  --k K          kernel scale K in [1, N]: kernels hold K/N of the PDF (default 1)\n"
         "  --device SEL   Vulkan device index or name substring (default: VSGL_DEVICE or auto)\n"
         "  --validation   enable the Khronos validation layer (any message fails the run)\n";
}

Options parseOptions(int argc, char** argv) {
  Options o;
  std::string_view kText = "1";  // as typed, for the range check once N is known
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw Error(std::string(arg) + ": missing value");
      return argv[++i];
    };
    if (arg == "--scene")
      o.scene = value();
    else if (arg == "--out")
      o.outDir = value();
    else if (arg == "--rsm")
      o.rsmSize = samples::parseUint(arg, value(), 16, 2048);
    else if (arg == "--count")
      o.count = samples::parseUint(arg, value(), 1, 65536);
    else if (arg == "--k")
      o.kernelScale = samples::parseFloat(arg, kText = value(), 1.0f, 65536.0f);
    else if (arg == "--frames")
      o.frames = samples::parseUint(arg, value(), 1, 100);
    else if (arg == "--device")
      o.device = value();
    else if (arg == "--validation")
      o.validation = true;
    else if (arg == "--help" || arg == "-h")
      o.help = true;
    else
      throw Error(std::string(arg) + ": unknown option (see --help)");
  }
  auto names = engine::builtinSceneNames();
  if (std::find(names.begin(), names.end(), o.scene) == names.end())
    throw Error("--scene: '" + o.scene + "' is not a built-in scene (cornell, atrium, checker)");
  // The attribute pyramids and the 4^l / M of both rules need a power-of-two square.
  if (!std::has_single_bit(o.rsmSize))
    throw Error("--rsm: " + std::to_string(o.rsmSize) + " is not a power of two");
  if (!(o.kernelScale >= 1.0f && o.kernelScale <= float(o.count)))
    throw Error("--k: " + std::string(kText) + " is outside [1, N = " + std::to_string(o.count) +
                "]");
  if (o.outDir.empty()) throw Error("--out: empty path");
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
  std::vector<glm::dvec3> kernels;
};

// GPU time of the final-step passes in the structure of [S3] Table 1 (lower row): additional
// RSM (flux + attributes), mipmapping, filtered sampling; the rules alternate frame by frame so
// that drift on a shared machine hits both alike. The RSM rasterisation is reported apart (the
// paper's RSM rendering is not part of its Table 1 rows).
void printTimings(engine::Context& ctx, const Options& o, const engine::SceneGpu& scene,
                  engine::Rasterizer& rasterizer, engine::GBufferResolve& resolve,
                  gi::ReflectiveShadowMap& rsm, const gi::MipPyramid& mips,
                  gi::VsglAttributes& attributes, gi::VsglGenerator& generator,
                  const gi::RsmView& view, const engine::Light& light) {
  const char* passes[] = {"rsm raster", "rsm flux", "vsgl attributes", "attribute mipmapping",
                          "filtered sampling"};
  std::map<std::string, std::vector<double>> times[2];
  engine::GpuProfiler profiler(ctx);
  for (uint32_t frame = 0; frame < 2 * (o.frames + 1); ++frame) {
    const uint32_t rule = frame % 2 ? VSGL_RULE_MODIFIED : VSGL_RULE_TOK15;
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      profiler.beginFrame(cmd);
      rsm.record(cmd, scene, rasterizer, resolve, view, light, &profiler);
      attributes.record(cmd, rsm.vpls(), rsm.surface(), view, mips, &profiler);
      generator.record(cmd, attributes, view, {o.count, o.kernelScale, rule}, &profiler);
    });
    if (frame < 2) continue;  // warm-up: pipelines compile at their first dispatch
    for (const auto& p : profiler.results()) times[rule][p.name].push_back(p.ms);
  }
  std::printf("GPU time per pass, median of %u frames (ms)      Tok15   modified\n", o.frames);
  double total[2] = {0.0, 0.0};
  for (const char* pass : passes) {
    double t[2] = {engine::median(times[0][pass]), engine::median(times[1][pass])};
    std::printf("  %-42s %8.3f %8.3f\n", pass, t[0], t[1]);
    if (std::string(pass) != "rsm raster")
      for (int r = 0; r < 2; ++r) total[r] += t[r];
  }
  std::printf("  %-42s %8.3f %8.3f  (modified / Tok15 = %.3f)\n",
              "additional RSM + mipmapping + filtered sampling", total[0], total[1],
              total[1] / total[0]);
}

int run(const Options& o) {
  if (o.help) {
    std::printf("%s", usage());
    return 0;
  }
  std::error_code ec;
  std::filesystem::create_directories(o.outDir, ec);
  if (ec) throw Error(o.outDir + ": cannot create output directory: " + ec.message());

  engine::Scene scene = engine::makeBuiltinScene(o.scene);
  const engine::Light& light = scene.lights.at(0);
  const gi::RsmView view = gi::makeRsmView(scene, light, o.rsmSize);

  engine::Context ctx({o.validation, o.device});
  std::printf("device: %s (%s)\nscene: %s, light '%s', RSM %u^2, N = %u, K = %g\n",
              ctx.info().name.c_str(), ctx.info().driver.c_str(), scene.source.c_str(),
              light.name.c_str(), o.rsmSize, o.count, double(o.kernelScale));
  engine::SceneGpu gpuScene = engine::uploadScene(ctx, scene);
  engine::Rasterizer rasterizer(ctx);
  engine::GBufferResolve resolve(ctx);
  gi::ReflectiveShadowMap rsm(ctx, o.rsmSize);
  gi::MipPyramid mips(ctx);
  gi::VsglAttributes attributes(ctx, o.rsmSize);
  gi::VsglGenerator generator(ctx, o.count);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    rsm.record(cmd, gpuScene, rasterizer, resolve, view, light);
    attributes.record(cmd, rsm.vpls(), rsm.surface(), view, mips);
  });

  // The PDF the generator warps: alpha of the diffuse-axis pyramid (shared/vsgl_attributes.h).
  const std::vector<glm::vec4> texels =
      attributes.pyramid(VSGL_ATTR_DIFFUSE_AXIS).readbackRgba32f(ctx, 0);
  std::vector<double> pdfBase;
  for (const glm::vec4& t : texels) pdfBase.push_back(t.w);
  const gi::ScalarPyramid pdf = gi::makeScalarPyramid(pdfBase, o.rsmSize);

  std::vector<RuleRun> runs{{"Tok15 [T15]", VSGL_RULE_TOK15, {}},
                            {"modified FIS [S3]", VSGL_RULE_MODIFIED, {}}};
  for (RuleRun& r : runs) {
    const gi::VsglSettings settings{o.count, o.kernelScale, r.rule};
    ctx.submitAndWait(
        [&](VkCommandBuffer cmd) { generator.record(cmd, attributes, view, settings); });
    const auto vsgls = generator.vsgls().readbackAs<gpu::Vsgl>(ctx);
    for (uint32_t i = 0; i < o.count; ++i) r.kernels.emplace_back(glm::dvec3(vsgls[i].kernel));
    const gi::KernelCoverage c = gi::measureCoverage(pdf, r.kernels);
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
    drawPdf(canvas, panel, pdfBase, o.rsmSize);
    // Centres on top of every square, so that none hides under a neighbour's outline.
    for (const glm::dvec3& k : runs[i].kernels) drawKernel(canvas, panel, k, o.rsmSize);
    for (const glm::dvec3& k : runs[i].kernels) drawCentre(canvas, panel, k, o.rsmSize);
  }
  printTimings(ctx, o, gpuScene, rasterizer, resolve, rsm, mips, attributes, generator, view,
               light);

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
