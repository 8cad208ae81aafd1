// vsgl_viewer: an interactive host of the public API (docs/viewer.md). A window shows the frame
// that vsgl_render would write for the same view and settings, with a panel for every setting,
// the scene, camera and lights, debug views, a split screen of two methods and the pass times.
// The frame renders on its own thread and device (render_worker.h), so the panel stays
// responsive on a slow device. --script replays input by frame, --frames and --screenshot make
// it a batch program for tests, --record writes the camera and light path for vsgl_flicker.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "app_state.h"
#include "engine/gltf.h"
#include "engine/image_io.h"
#include "engine/profiler.h"
#include "options.h"
#include "panel.h"
#include "program_exit.h"
#include "render_worker.h"
#include "scene_files.h"
#include "settings_fields.h"
#include "view_path.h"
#include "window.h"

namespace {

using namespace viewer;

std::array<uint8_t, VK_UUID_SIZE> deviceUuid(const engine::Context& ctx) {
  VkPhysicalDeviceIDProperties id{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &id};
  vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
  std::array<uint8_t, VK_UUID_SIZE> uuid{};
  std::copy(std::begin(id.deviceUUID), std::end(id.deviceUUID), uuid.begin());
  return uuid;
}

// Where the frame lies in the window (fitted and centred, as Window::present draws it).
Rect frameRect(const Rect& area, uint32_t width, uint32_t height) {
  const double scale = std::min(double(area.width) / width, double(area.height) / height);
  const int w = int(width * scale), h = int(height * scale);
  return {area.x + (area.width - w) / 2, area.y + (area.height - h) / 2, w, h};
}

// Mouse and keys, where the panel does not take them (ImGui's WantCapture flags).
void handleInput(GLFWwindow* window, AppState& state, float dt, const Rect& shown,
                 uint32_t frameWidth, uint32_t frameHeight, bool& screenshot) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureMouse) {
    const ImVec2 d = io.MouseDelta;
    const bool moved = d.x != 0.0f || d.y != 0.0f;
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && moved) {
      state.camera.turn(-0.3f * d.x, -0.3f * d.y);
      state.changed();
    }
    if (ImGui::IsMouseDown(ImGuiMouseButton_Right) && moved)
      state.turnLight(-0.3f * d.x, -0.3f * d.y);
    if (ImGui::IsMouseDown(ImGuiMouseButton_Middle) && moved) {
      const float s = 0.002f * state.camera.speed();
      state.camera.move({-s * d.x, s * d.y, 0.0f});
      state.changed();
    }
    if (io.MouseWheel != 0.0f) {
      state.camera.zoom(std::pow(0.9f, io.MouseWheel));
      state.changed();
    }
    // A click without a drag picks the VSGL of the pixel under the mouse.
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Left, 0.0f).x == 0.0f &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Left, 0.0f).y == 0.0f && shown.width > 0) {
      const float px = io.MousePos.x * io.DisplayFramebufferScale.x - float(shown.x);
      const float py = io.MousePos.y * io.DisplayFramebufferScale.y - float(shown.y);
      if (px >= 0 && py >= 0 && px < float(shown.width) && py < float(shown.height)) {
        state.pick =
            std::array<uint32_t, 2>{uint32_t(px * float(frameWidth) / float(shown.width)),
                                    uint32_t(py * float(frameHeight) / float(shown.height))};
        state.changed();
      }
    }
  }
  if (io.WantCaptureKeyboard) return;
  auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
  const float step = dt * state.camera.speed();
  const glm::vec3 camera(key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q),
                         key(GLFW_KEY_W) - key(GLFW_KEY_S));
  if (camera != glm::vec3(0.0f)) {
    state.camera.move(step * camera);
    state.changed();
  }
  const glm::vec3 light(key(GLFW_KEY_RIGHT) - key(GLFW_KEY_LEFT),
                        key(GLFW_KEY_PAGE_UP) - key(GLFW_KEY_PAGE_DOWN),
                        key(GLFW_KEY_DOWN) - key(GLFW_KEY_UP));
  if (light != glm::vec3(0.0f)) state.moveLight(step * light);
  screenshot |= ImGui::IsKeyPressed(GLFW_KEY_F12, false);
}

// BASE.exr (the view's linear image), BASE.png (the picture shown), BASE_window.png (the window,
// panel included), BASE.gltf (the scene with the camera and lights shown) and BASE.settings.
void writeScreenshot(const std::string& base, const FrameResult& r, const Window& window,
                     AppState& state) {
  const std::filesystem::path parent = std::filesystem::path(base).parent_path();
  if (!parent.empty()) samples::createOutputDirectory(parent.string());
  const FrameRequest& q = r.request;
  const samples::FrameImages& f = r.images;
  const engine::ImageRgba32f& linear = q.mode == ViewMode::Direct            ? f.direct
                                       : q.mode == ViewMode::IndirectDiffuse ? f.diffuse
                                       : q.mode == ViewMode::IndirectGlossy  ? f.glossy
                                                                             : f.final;
  engine::writeExr(base + ".exr", linear);
  engine::writePng(base + ".png", int(r.width), int(r.height), r.rgba);
  if (!window.captured().empty())
    engine::writePng(base + "_window.png", window.capturedSize()[0], window.capturedSize()[1],
                     window.captured());
  // The scene as this frame showed it: its lights, and its camera first, named "viewer".
  engine::Scene shown = *q.scene;
  shown.lights = q.lights;
  engine::Camera camera = q.camera;
  camera.name = "viewer";
  shown.cameras.insert(shown.cameras.begin(), camera);
  engine::writeGltf(shown, base + ".gltf");
  std::ofstream settings(base + ".settings");
  settings << samples::formatSettings(q.settings);
  if (!settings) throw engine::Error(base + ".settings: cannot write");
  std::string batch = "vsgl_render --scene " + base + ".gltf --camera viewer --light none" +
                      " --settings " + base + ".settings --width " + std::to_string(r.width) +
                      " --height " + std::to_string(r.height);
  if (!q.environment.empty()) batch += " --environment " + q.environment;
  if (q.exposureEv) batch += " --exposure " + std::to_string(*q.exposureEv);
  if (r.visibilityVsgl >= 0) batch += " --debug-vsgl " + std::to_string(r.visibilityVsgl);
  // The files of vsgl_render's that must equal BASE.exr and BASE.png: its frame in the modes
  // that show the frame (vsgl_render writes neither the direct light nor one indirect term
  // alone), and the debug picture of the mode; nothing for a split screen.
  const bool frame = !q.right && (q.mode == ViewMode::Final || q.mode == ViewMode::VsglLobes ||
                                  q.mode == ViewMode::Visibility || q.mode == ViewMode::Levels);
  const char* png = q.mode == ViewMode::VsglLobes    ? "_vsgls.png"
                    : q.mode == ViewMode::Visibility ? "_visibility.png"
                    : q.mode == ViewMode::Levels     ? "_levels.png"
                                                     : ".png";
  const std::string compare = frame ? std::string(".exr ") + png : "";
  state.status = "wrote " + base + ".{exr,png,gltf,settings}, " + base + "_window.png";
  std::printf("%s\n  batch: %s\n  batch compare: %s\n", state.status.c_str(), batch.c_str(),
              compare.c_str());
  std::fflush(stdout);
}

int run(const Options& o) {
  if (o.common.help) {
    std::printf("%s", usage());
    return 0;
  }
  AppState state = initialState(o);
  if (!state.status.empty()) std::printf("%s\n", state.status.c_str());
  const std::vector<ScriptEvent> script =
      o.script.empty() ? std::vector<ScriptEvent>{} : readScript(o.script);
  auto ctx = std::make_unique<engine::Context>(
      engine::ContextOptions{o.common.validation, o.common.device});
  PanelContext panel;
  panel.device = ctx->info().name + " (" + ctx->info().driver + ")";
  Window window("vsgl_viewer: " + state.sceneName, o.width, o.height, o.common.validation,
                deviceUuid(*ctx));
  RenderWorker worker(std::move(ctx));
  std::optional<samples::ViewPathWriter> recorder;
  if (!o.record.empty()) recorder.emplace(o.record);

  // A script or --frames: one rendered frame per step, steps 0 .. steps - 1.
  const bool stepped = !script.empty() || o.frames > 0;
  const uint64_t steps = std::max<uint64_t>(o.frames, script.empty() ? 0 : script.back().frame + 1);
  uint64_t step = 0, posted = ~uint64_t{0};
  bool waiting = false;
  size_t nextEvent = 0;
  // Screenshots of the step being rendered, and those due now (its frame has arrived).
  std::vector<std::string> stepShots, shots;
  std::optional<FrameResult> last;
  TimingHistory history;
  const auto start = std::chrono::steady_clock::now();
  auto previous = start;
  uint64_t panelFrames = 0, rendered = 0;
  std::vector<double> frameMs;  // each frame's GPU time ("host frame": the module included)
  while (!window.shouldClose()) {
    glfwPollEvents();
    const auto now = std::chrono::steady_clock::now();
    const float dt = std::min(std::chrono::duration<float>(now - previous).count(), 0.1f);
    previous = now;
    panel.uiFps = 0.9f * panel.uiFps + 0.1f / std::max(dt, 1e-3f);

    const auto [windowWidth, windowHeight] = window.size();
    const Rect area{0, 0, windowWidth, windowHeight};
    const uint32_t width = std::max(1u, uint32_t(std::lround(float(windowWidth) * state.scale)));
    const uint32_t height = std::max(1u, uint32_t(std::lround(float(windowHeight) * state.scale)));
    panel.renderWidth = width;
    panel.renderHeight = height;
    bool stepDone = false;
    if (std::optional<FrameResult> result = worker.take()) {
      if (!result->error.empty() && stepped) throw engine::Error(result->error);
      if (result->error.empty()) {
        history.add(*result);
        ++rendered;
        frameMs.push_back(double(history.host.back()));
        window.setImage(result->rgba, result->width, result->height);
        if (recorder && recorder->frames() == samples::kMaxPathFrames) {
          state.status = "recording stopped at " + std::to_string(samples::kMaxPathFrames) +
                         " frames (vsgl_flicker replays at most that many)";
          recorder.reset();
        }
        if (recorder) recorder->add({result->request.camera, result->request.lights});
        last = std::move(result);
      } else {
        last->error = result->error;  // the frame before it stays on screen
      }
      if (stepped && last->serial == posted) {
        waiting = false;
        stepDone = true;
        ++step;
        shots = std::move(stepShots);  // the step's screenshots show this frame
        stepShots.clear();
      }
    }
    panel.last = last ? &*last : nullptr;
    panel.history = &history;
    panel.recording = recorder.has_value();
    window.beginPanel();
    const PanelRequests requests = drawPanel(state, panel);
    bool screenshot = requests.screenshot;
    if (requests.toggleRecording) {
      if (recorder) {
        state.status = "recorded " + std::to_string(recorder->frames()) + " frames";
        recorder.reset();
      } else {
        recorder.emplace(o.record.empty() ? "viewer_path.txt" : o.record);
        state.status =
            "recording to " + (o.record.empty() ? std::string("viewer_path.txt") : o.record);
      }
    }
    if (!stepped)
      handleInput(window.glfw(), state, dt,
                  last ? frameRect(area, last->width, last->height) : Rect{}, width, height,
                  screenshot);

    if (stepped && !waiting && step < steps) {
      for (; nextEvent < script.size() && script[nextEvent].frame == step; ++nextEvent) {
        if (script[nextEvent].command == "screenshot")
          stepShots.push_back(script[nextEvent].args[0]);
        else if (std::string problem = state.apply(script[nextEvent]); !problem.empty())
          std::fprintf(stderr, "vsgl_viewer: %s (the %s stays as it was)\n", problem.c_str(),
                       script[nextEvent].command.c_str());
      }
      state.changed();  // every step renders one frame
      worker.post(state.request(width, height));
      posted = state.serial;
      waiting = true;
    } else if (!stepped && state.serial != posted) {
      worker.post(state.request(width, height));
      posted = state.serial;
    }

    const bool finished = stepped && stepDone && step >= steps;
    if (finished && !o.screenshot.empty()) shots.push_back(o.screenshot);
    const bool capture = !shots.empty() || (screenshot && last);
    window.present(area, capture);
    if (capture) {
      if (screenshot && shots.empty()) shots.push_back("viewer_screenshot");
      for (const std::string& base : shots) writeScreenshot(base, *last, window, state);
      shots.clear();
    }
    ++panelFrames;
    if (finished) break;
    // At most --panel-fps panel frames a second (scripts run as fast as frames come).
    if (!stepped)
      std::this_thread::sleep_until(now + std::chrono::microseconds(1000000 / o.panelFps));
    if (o.seconds > 0.0f &&
        std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count() >= o.seconds)
      break;
  }
  // What a frame costs against how fast the panel ran meanwhile (docs/viewer.md).
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "panel: %llu frames in %.1f s (%.1f per second); renderer: %llu frames, host frame "
      "median %.1f ms on the GPU timer\n",
      static_cast<unsigned long long>(panelFrames), wall, double(panelFrames) / wall,
      static_cast<unsigned long long>(rendered), engine::median(frameMs));
  const uint32_t messages = worker.validationMessageCount() + window.validationMessageCount();
  if (messages > 0) {
    for (const std::string& m : window.validationMessages())
      std::fprintf(stderr, "window validation: %s\n", m.c_str());
    std::fprintf(stderr, "vsgl_viewer: error: %u validation messages\n", messages);
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return samples::guardedMain("vsgl_viewer", [&] { return run(parseOptions(argc, argv)); });
}
