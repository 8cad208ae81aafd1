#include "render_worker.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "debug_views.h"
#include "engine/gbuffer_reference.h"
#include "engine/profiler.h"
#include "engine/scene_gpu.h"
#include "engine/tonemap.h"
#include "gi_host.h"
#include "reference/vsgl_shade_reference.h"
#include "scene_files.h"

namespace viewer {

const char* viewModeWord(ViewMode mode) {
  switch (mode) {
    case ViewMode::Final:
      return "final";
    case ViewMode::Direct:
      return "direct";
    case ViewMode::IndirectDiffuse:
      return "diffuse";
    case ViewMode::IndirectGlossy:
      return "glossy";
    case ViewMode::VsglLobes:
      return "lobes";
    case ViewMode::Visibility:
      return "visibility";
    case ViewMode::Levels:
      return "levels";
  }
  return "?";
}

ViewMode parseViewMode(const std::string& option, const std::string& word) {
  std::string accepted;
  for (ViewMode m : kViewModes) {
    if (word == viewModeWord(m)) return m;
    accepted += (accepted.empty() ? "" : ", ") + std::string(viewModeWord(m));
  }
  throw engine::Error(option + ": '" + word + "' is not one of " + accepted);
}

namespace {

// Shadow maps with about as many texels across as the image has pixels (vsgl_render's rule).
uint32_t shadowResolution(uint32_t width, uint32_t height) {
  uint32_t resolution = 256;
  while (resolution < std::max(width, height) / 2 && resolution < 2048) resolution *= 2;
  return resolution;
}

// The VSGL that sends `pixel` the most light, unshadowed (the CPU twin of the shading without
// visibility; the ISM would need the atlas). -1 when the pixel sees the sky or nothing lights it.
int32_t strongestVsgl(const engine::GBufferData& g, const engine::View& view,
                      std::array<uint32_t, 2> pixel, std::span<const gpu::Vsgl> vsgls,
                      const gi::Settings& settings) {
  if (pixel[0] >= g.width || pixel[1] >= g.height) return -1;
  const engine::GBufferSample& s = g.at(pixel[0], pixel[1]);
  if (s.background()) return -1;
  const glm::dvec2 ndc((pixel[0] + 0.5) / g.width * 2.0 - 1.0,
                       (pixel[1] + 0.5) / g.height * 2.0 - 1.0);
  const glm::dvec4 p = glm::dmat4(view.invViewProj) * glm::dvec4(ndc, double(s.depth), 1.0);
  gi::ShadeReceiver r;
  r.position = glm::dvec3(p) / p.w;
  r.normal = s.normal;
  r.view = glm::normalize(glm::dvec3(glm::inverse(glm::dmat4(view.view))[3]) - r.position);
  r.albedo = s.diffuse;
  r.f0 = s.f0;
  r.f90 = s.f90;
  r.roughness = s.roughness;
  int32_t best = -1;
  double bestLuminance = 0.0;
  for (size_t i = 0; i < vsgls.size(); ++i) {
    const gi::IndirectRadiance l =
        gi::shadeReference(r, vsgls.subspan(i, 1), settings.glossy, settings.planarEmitters);
    const glm::dvec3 sum = l.diffuse + l.glossy;
    const double luminance = 0.2126 * sum.r + 0.7152 * sum.g + 0.0722 * sum.b;
    if (luminance > bestLuminance) {
      bestLuminance = luminance;
      best = int32_t(i);
    }
  }
  return best;
}

}  // namespace

// Everything the render thread keeps between frames.
struct RenderWorker::State {
  std::unique_ptr<engine::Context> ctx;
  std::shared_ptr<const engine::Scene> sceneSource;  // the request's pointer, to see changes
  engine::Scene scene;                               // a copy with the request's lights
  std::optional<engine::SceneGpu> gpuScene;
  std::unique_ptr<samples::HostFrame> host;
  std::unique_ptr<gi::IndirectLighting> left, right;
  std::shared_ptr<const engine::ImageRgba32f> environment;
  std::unique_ptr<engine::GpuProfiler> profiler;
  int32_t visibilityVsgl = -1;
  uint64_t frames = 0;
  // The G-buffer's number (gi::FrameInput::gbufferGeneration): a new one whenever the host
  // renders a different G-buffer (scene, size or camera), so that the module keeps the rest.
  uint64_t gbufferGeneration = 0;
  glm::mat4 gbufferViewProj{0.0f};

  // A module for `settings` at the frame's size: the one there, with new settings, unless a
  // creation field changed (setSettings refuses) or it has another size.
  void prepare(std::unique_ptr<gi::IndirectLighting>& module, const gi::Settings& settings,
               uint32_t width, uint32_t height) {
    if (module && module->setSettings(settings)) return;
    module.reset();
    module = samples::createIndirect(*ctx, settings, width, height, *gpuScene, scene);
    if (environment)
      samples::check(
          module->setEnvironment({uint32_t(environment->width), uint32_t(environment->height),
                                  environment->pixels.data()}));
  }

  FrameResult render(const FrameRequest& request);
};

FrameResult RenderWorker::State::render(const FrameRequest& r) {
  FrameResult result;
  result.serial = r.serial;
  result.width = r.width;
  result.height = r.height;
  if (r.scene != sceneSource) {  // a new scene: upload it, and everything sized by it goes
    left.reset();
    right.reset();
    host.reset();
    gpuScene.reset();
    scene = *r.scene;
    scene.lights = r.lights;
    gpuScene.emplace(engine::uploadScene(*ctx, scene));
    ++gbufferGeneration;
    sceneSource = r.scene;
    visibilityVsgl = -1;
  }
  if (r.environmentImage != environment) {
    environment = r.environmentImage;
    left.reset();
    right.reset();
  }
  const bool lightsChanged = !host || scene.lights != r.lights;
  scene.lights = r.lights;
  if (!host || host->width() != r.width || host->height() != r.height) {
    left.reset();
    right.reset();
    host = std::make_unique<samples::HostFrame>(
        *ctx, scene, r.width, r.height,
        engine::DirectLightSettings{shadowResolution(r.width, r.height), true});
    ++gbufferGeneration;
  } else if (lightsChanged) {
    host->setLights(*ctx, scene);
  }

  engine::Camera camera = r.camera;
  engine::View view = engine::cameraView(camera, r.width, r.height);
  result.view = view;
  result.request = r;
  const size_t bouncing = std::min<size_t>(scene.lights.size(), gi::kMaxLights);
  const bool indirect = r.indirect && (bouncing > 0 || environment);
  if (!indirect) {
    left.reset();
    right.reset();
    result.note = r.indirect ? "no light to bounce: direct light only" : "indirect light off";
  }
  if (indirect) prepare(left, r.settings, r.width, r.height);
  if (indirect && r.right)
    prepare(right, *r.right, r.width, r.height);
  else
    right.reset();

  if (view.viewProj != gbufferViewProj) ++gbufferGeneration;
  gbufferViewProj = view.viewProj;
  gi::FrameInput input;
  if (indirect) {
    input = samples::frameInput(host->gbuffer(), view,
                                std::span<const engine::Light>(scene.lights.data(), bouncing));
    input.gbufferGeneration = gbufferGeneration;
    input.sceneGeneration = 1;  // a new scene is a new module's (setScene), never edited in place
  }
  gi::FrameOutput leftOut, rightOut;
  if (!profiler) profiler = std::make_unique<engine::GpuProfiler>(*ctx);
  ctx->submitAndWait([&](VkCommandBuffer cmd) {
    profiler->beginFrame(cmd);
    engine::ProfileScope total(profiler.get(), cmd, "host frame");
    host->record(cmd, *gpuScene, view, profiler.get());
    if (left) samples::check(left->record(cmd, input, &leftOut));
    if (right) samples::check(right->record(cmd, input, &rightOut));
  });
  ++frames;
  result.frameNumber = frames;
  for (const auto& pass : profiler->results())
    result.passes.push_back({pass.name, pass.ms, pass.dispatches});
  if (left) {
    for (auto pass : left->lastFrameTimes()) {
      pass.name = "gi " + pass.name;
      result.passes.push_back(pass);
    }
    result.plan = left->lastPlan().reasons;
    const std::vector<std::string>& kept = left->lastPlan().reuse.reasons;
    result.plan.insert(result.plan.end(), kept.begin(), kept.end());
    result.vsglCount = leftOut.vsglCount;
  }
  if (right)
    for (auto pass : right->lastFrameTimes()) {
      pass.name = "gi right " + pass.name;
      result.passes.push_back(pass);
    }

  const engine::ImageRgba32f* env = environment.get();
  result.images = samples::readFrame(*ctx, *host, left ? &leftOut : nullptr, view, env);
  std::vector<gpu::Vsgl> vsgls;
  if (left && leftOut.vsglCount > 0) vsgls = samples::readVsgls(*ctx, leftOut);
  if (r.pick && !vsgls.empty()) {
    const engine::GBufferData g = engine::readbackGBuffer(*ctx, host->gbuffer());
    const int32_t picked = strongestVsgl(g, view, *r.pick, vsgls, r.settings);
    if (picked >= 0) visibilityVsgl = picked;
  }
  if (visibilityVsgl >= int32_t(vsgls.size())) visibilityVsgl = -1;
  if (visibilityVsgl < 0 && !vsgls.empty()) visibilityVsgl = int32_t(samples::brightestVsgl(vsgls));
  // The visibility view: one more frame of the module with that VSGL's visibility written out,
  // as vsgl_render makes its _visibility.png.
  gi::FrameOutput visibilityOut;
  if (r.mode == ViewMode::Visibility && left && r.settings.ismEnabled && visibilityVsgl >= 0) {
    gi::Settings debug = r.settings;
    debug.debugVsgl = visibilityVsgl;
    samples::check(left->setSettings(debug));
    ctx->submitAndWait(
        [&](VkCommandBuffer cmd) { samples::check(left->record(cmd, input, &visibilityOut)); });
    samples::check(left->setSettings(r.settings));
    result.visibilityVsgl = visibilityVsgl;
  }

  // The picture of the mode, tone-mapped like vsgl_render's files of the same name.
  const engine::ToneMapSettings toneMap{r.exposureEv};
  auto picture = [&](const samples::FrameImages& f, const gi::FrameOutput& out,
                     const gi::FrameOutput& visibility,
                     const engine::ToneMapSettings& tm) -> std::vector<uint8_t> {
    switch (r.mode) {
      case ViewMode::Direct:
        return engine::toneMap(f.direct, tm);
      case ViewMode::IndirectDiffuse:
        return engine::toneMap(f.diffuse, tm);
      case ViewMode::IndirectGlossy:
        return engine::toneMap(f.glossy, tm);
      case ViewMode::VsglLobes:
        return samples::drawVsglLobes(engine::toneMap(f.final, tm), int(r.width), int(r.height),
                                      vsgls, view.viewProj);
      case ViewMode::Visibility:
        if (visibility.debugVisibility.image)
          return samples::greyscale(
              samples::readR32f(*ctx, visibility.debugVisibility, r.width, r.height, "visibility"));
        result.note = "no visibility to show (no VSGL, or ISMs off)";
        return engine::toneMap(f.final, tm);
      case ViewMode::Levels:
        if (out.shadingLevels.image)
          return samples::levelColours(
              engine::toneMap(f.final, tm),
              samples::readR32f(*ctx, out.shadingLevels, r.width, r.height, "levels"));
        result.note = "no levels to show (adaptive shading off)";
        return engine::toneMap(f.final, tm);
      case ViewMode::Final:
        break;
    }
    return engine::toneMap(f.final, tm);
  };
  if (!right) {
    result.rgba = picture(result.images, leftOut, visibilityOut, toneMap);
  } else {
    // Both halves at the left image's exposure, so that brightness compares.
    const engine::ImageRgba32f& shown = r.mode == ViewMode::IndirectDiffuse  ? result.images.diffuse
                                        : r.mode == ViewMode::IndirectGlossy ? result.images.glossy
                                        : r.mode == ViewMode::Direct         ? result.images.direct
                                                                             : result.images.final;
    const engine::ToneMapSettings shared{std::log2(engine::exposureScale(shown, toneMap))};
    result.rgba = picture(result.images, leftOut, visibilityOut, shared);
    const samples::FrameImages rightImages = samples::readFrame(*ctx, *host, &rightOut, view, env);
    const std::vector<uint8_t> rightRgba = picture(rightImages, rightOut, {}, shared);
    for (uint32_t y = 0; y < r.height; ++y)
      for (uint32_t x = r.width / 2; x < r.width; ++x) {
        const size_t i = (size_t{y} * r.width + x) * 4;
        const bool divider = x == r.width / 2;
        for (int c = 0; c < 4; ++c) result.rgba[i + c] = divider ? 255 : rightRgba[i + c];
      }
  }
  return result;
}

RenderWorker::RenderWorker(std::unique_ptr<engine::Context> ctx)
    : state_(std::make_unique<State>()) {
  state_->ctx = std::move(ctx);
  thread_ = std::thread([this] { run(); });
}

RenderWorker::~RenderWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void RenderWorker::post(FrameRequest request) {
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(request);
    pendingIsNew_ = true;
  }
  wake_.notify_all();
}

std::optional<FrameResult> RenderWorker::take() {
  std::lock_guard lock(mutex_);
  std::optional<FrameResult> out = std::move(result_);
  result_.reset();
  return out;
}

uint32_t RenderWorker::validationMessageCount() const {
  return state_->ctx->validationMessageCount();
}

void RenderWorker::run() {
  for (;;) {
    FrameRequest request;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock,
                 [&] { return stop_ || (pending_ && (pendingIsNew_ || pending_->continuous)); });
      if (stop_) return;
      request = *pending_;
      pending_->pick.reset();  // a pick happens once
      pendingIsNew_ = false;
    }
    FrameResult result;
    try {
      result = state_->render(request);
    } catch (const std::exception& e) {
      result = FrameResult{};
      result.serial = request.serial;
      result.error = e.what();
      std::lock_guard lock(mutex_);
      // A request that fails is not retried until something changes.
      if (pending_ && pending_->serial == request.serial) pending_->continuous = false;
    }
    std::lock_guard lock(mutex_);
    result_ = std::move(result);
  }
}

}  // namespace viewer
