#include "panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include "engine/builtin_scenes.h"
#include "engine/environments.h"
#include "settings_fields.h"

namespace viewer {
namespace {

// One settings field as a widget of its kind; true when the value changed. The label carries the
// unit, the tooltip the range, what it does and whether changing it recreates the module.
bool fieldWidget(const samples::SettingField& f, gi::Settings& settings) {
  using Kind = samples::SettingField::Kind;
  std::string label = f.key;
  if (*f.unit) label += std::string(" (") + f.unit + ")";
  double value = f.get(settings);
  bool changed = false;
  switch (f.kind) {
    case Kind::Bool: {
      bool on = value != 0.0;
      if (ImGui::Checkbox(label.c_str(), &on)) {
        f.set(settings, on ? 1.0 : 0.0);
        changed = true;
      }
      break;
    }
    case Kind::Choice: {
      int current = 0;
      for (size_t i = 0; i < f.choices.size(); ++i)
        if (f.choices[i].second == uint32_t(value)) current = int(i);
      if (ImGui::BeginCombo(label.c_str(), f.choices[size_t(current)].first)) {
        for (size_t i = 0; i < f.choices.size(); ++i)
          if (ImGui::Selectable(f.choices[i].first, int(i) == current)) {
            f.set(settings, f.choices[i].second);
            changed = true;
          }
        ImGui::EndCombo();
      }
      break;
    }
    case Kind::Uint:
    case Kind::Int: {
      if (f.powerOfTwo) {  // a slider over the exponent: every position is a valid value
        int exponent = int(std::lround(std::log2(std::max(value, 1.0))));
        const int lo = int(std::lround(std::log2(std::max(f.min, 1.0))));
        const int hi = int(std::lround(std::log2(f.max)));
        char shown[32];
        std::snprintf(shown, sizeof(shown), "%.0f", std::exp2(double(exponent)));
        if (ImGui::SliderInt(label.c_str(), &exponent, lo, hi, shown)) {
          f.set(settings, std::exp2(double(exponent)));
          changed = true;
        }
      } else {
        int v = int(value);
        const bool logarithmic = f.max / std::max(f.min, 1.0) > 1000.0;
        if (ImGui::SliderInt(label.c_str(), &v, int(f.min), int(f.max), "%d",
                             logarithmic ? ImGuiSliderFlags_Logarithmic : 0)) {
          f.set(settings, std::clamp(double(v), f.min, f.max));
          changed = true;
        }
      }
      break;
    }
    case Kind::Float: {
      float v = float(value);
      const bool logarithmic = f.min > 0.0 && f.max / f.min > 1000.0;
      if (ImGui::SliderFloat(label.c_str(), &v, float(f.min), float(f.max), "%.4g",
                             logarithmic ? ImGuiSliderFlags_Logarithmic : 0)) {
        f.set(settings, std::clamp(double(v), f.min, f.max));
        changed = true;
      }
      break;
    }
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s\nrange [%g, %g]%s%s", f.help, f.min, f.max,
                      f.powerOfTwo ? ", a power of two" : "",
                      f.creation ? "\nchanging it recreates the module" : "");
  return changed;
}

void sceneSection(AppState& state) {
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  static std::string file, environmentFile;
  for (const std::string& name : engine::builtinSceneNames()) {
    if (ImGui::RadioButton(name.c_str(), state.sceneName == name) && state.sceneName != name)
      if (std::string e = state.load(name, ""); !e.empty()) state.status = e;
    ImGui::SameLine();
  }
  ImGui::NewLine();
  ImGui::InputText("glTF file", &file);
  ImGui::SameLine();
  if (ImGui::Button("Load"))  // a file that fails to load leaves the scene as it was
    if (std::string e = state.load(file, ""); !e.empty()) state.status = e;
  if (state.scene && state.scene->cameras.size() > 1 &&
      ImGui::BeginCombo("camera", "the file's cameras")) {
    for (size_t i = 0; i < state.scene->cameras.size(); ++i) {
      const engine::Camera& c = state.scene->cameras[i];
      const std::string label = std::to_string(i) + ": " + c.name;
      if (ImGui::Selectable(label.c_str())) {
        state.camera.reset(c, state.scene->bounds());
        state.changed();
      }
    }
    ImGui::EndCombo();
  }
  int mode = state.camera.mode == CameraControl::Mode::Orbit ? 0 : 1;
  ImGui::RadioButton("orbit", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("fly", &mode, 1);
  state.camera.mode = mode == 0 ? CameraControl::Mode::Orbit : CameraControl::Mode::Fly;
  ImGui::SameLine();
  if (ImGui::Button("reset camera")) {
    state.camera.reset(state.scene->cameras.empty() ? engine::defaultCamera(*state.scene)
                                                    : state.scene->cameras.front(),
                       state.scene->bounds());
    state.changed();
  }
  const std::vector<std::string> environments = engine::builtinEnvironmentNames();
  if (ImGui::BeginCombo("environment",
                        state.environment.empty() ? "none" : state.environment.c_str())) {
    if (ImGui::Selectable("none", state.environment.empty())) state.setEnvironment("");
    for (const std::string& e : environments)
      if (ImGui::Selectable(e.c_str(), state.environment == e))
        if (std::string error = state.setEnvironment(e); !error.empty()) state.status = error;
    ImGui::EndCombo();
  }
  ImGui::InputText("HDR/EXR file", &environmentFile);
  ImGui::SameLine();
  if (ImGui::Button("Load##environment"))  // a file that fails leaves the environment as it was
    if (std::string e = state.setEnvironment(environmentFile); !e.empty()) state.status = e;
  ImGui::TextDisabled("drag: turn, wheel: zoom, middle drag: pan, WASD QE: move");
}

void lightSection(AppState& state) {
  if (!ImGui::CollapsingHeader("Lights")) return;
  if (state.lights.empty()) {
    ImGui::TextDisabled("the scene has no light");
    return;
  }
  for (uint32_t i = 0; i < state.lights.size(); ++i) {
    const engine::Light& l = state.lights[i];
    const char* type = l.type == engine::LightType::Point  ? "point"
                       : l.type == engine::LightType::Spot ? "spot"
                                                           : "directional";
    const std::string label =
        std::to_string(i) + ": " + type + (l.name.empty() ? "" : " " + l.name);
    if (ImGui::RadioButton(label.c_str(), state.selectedLight == i)) state.selectedLight = i;
  }
  engine::Light& l = state.lights[std::min<size_t>(state.selectedLight, state.lights.size() - 1)];
  bool changed = false;
  if (l.type != engine::LightType::Directional)
    changed |= ImGui::DragFloat3("position (m)", &l.position.x, 0.01f);
  if (l.type != engine::LightType::Point) {
    if (ImGui::DragFloat3("direction", &l.direction.x, 0.01f, -1.0f, 1.0f) &&
        glm::length(l.direction) > 1e-3f) {
      l.direction = glm::normalize(l.direction);
      changed = true;
    }
  }
  changed |= ImGui::ColorEdit3("colour", &l.color.x);
  changed |= ImGui::SliderFloat("intensity", &l.intensity, 0.0f, 1000.0f, "%.3g",
                                ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("W/sr (point, spot) or W/m^2 (directional)");
  if (l.type == engine::LightType::Spot) {
    changed |= ImGui::SliderAngle("outer cone", &l.outerConeAngle, 1.0f, 90.0f);
    l.innerConeAngle = std::min(l.innerConeAngle, l.outerConeAngle * 0.999f);
    changed |= ImGui::SliderAngle("inner cone", &l.innerConeAngle, 0.0f,
                                  glm::degrees(l.outerConeAngle) * 0.999f);
  }
  if (changed) state.changed();
  ImGui::TextDisabled("right drag: turn, arrows / PgUp PgDn: move");
}

void viewSection(AppState& state, const PanelContext& context) {
  if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
  int mode = int(state.mode);
  for (ViewMode m : kViewModes) {
    if (ImGui::RadioButton(viewModeWord(m), &mode, int(m))) {
      state.mode = m;
      state.changed();
    }
    if (m == ViewMode::IndirectDiffuse || m == ViewMode::Final) continue;
    ImGui::SameLine();
  }
  ImGui::NewLine();
  if (state.mode == ViewMode::Visibility)
    ImGui::TextDisabled("click a pixel: the VSGL that lights it most (now %d)",
                        context.last ? context.last->visibilityVsgl : -1);
  if (ImGui::BeginCombo("split screen", state.split.empty() ? "off" : state.split.c_str())) {
    if (ImGui::Selectable("off", state.split.empty())) {
      state.split.clear();
      state.changed();
    }
    for (const char* const* w = methodWords(); *w; ++w)
      if (ImGui::Selectable(*w, state.split == *w)) {
        state.split = *w;
        state.changed();
      }
    ImGui::EndCombo();
  }
  if (!state.split.empty())
    ImGui::TextDisabled("left: %s, right: %s", methodWord(state.settings), state.split.c_str());
  bool fixed = state.exposureEv.has_value();
  float ev = state.exposureEv.value_or(0.0f);
  if (ImGui::Checkbox("fixed exposure", &fixed)) {
    state.exposureEv = fixed ? std::optional<float>(ev) : std::nullopt;
    state.changed();
  }
  if (fixed && ImGui::SliderFloat("exposure (EV)", &ev, -16.0f, 16.0f)) {
    state.exposureEv = ev;
    state.changed();
  }
  if (ImGui::SliderFloat("resolution scale", &state.scale, 0.1f, 1.0f, "%.2f")) state.changed();
  ImGui::TextDisabled("frame %u x %u", context.renderWidth, context.renderHeight);
  // The levers on a slow device, in reach: resolution scale above, adaptive shading here.
  if (ImGui::Checkbox("adaptive shading", &state.settings.adaptive.enabled)) state.changed();
  ImGui::SameLine();
  if (ImGui::Checkbox("indirect light", &state.indirect)) state.changed();
  ImGui::SameLine();
  if (ImGui::Checkbox("continuous", &state.continuous)) state.changed();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("render again when nothing changed");
}

void settingsSection(AppState& state) {
  if (!ImGui::CollapsingHeader("Settings (gi::Settings)")) return;
  gi::Settings edited = state.settings;
  bool changed = false;
  const char* group = nullptr;
  bool open = false;
  for (const samples::SettingField& f : samples::settingFields()) {
    if (!group || std::string(group) != f.group) {
      if (group && open) ImGui::TreePop();
      group = f.group;
      open = ImGui::TreeNodeEx(group, std::string(group) == "VSGLs" ? ImGuiTreeNodeFlags_DefaultOpen
                                                                    : ImGuiTreeNodeFlags_None);
    }
    if (open) changed |= fieldWidget(f, edited);
  }
  if (group && open) ImGui::TreePop();
  if (!changed) return;
  // Cross-field limits (vsglCount within maxVsglCount, ...): the edit is kept only when valid.
  if (edited.vsglCount > edited.maxVsglCount && edited.maxVsglCount != 0)
    edited.maxVsglCount = edited.vsglCount;
  if (std::string bad = gi::validateSettings(edited); !bad.empty()) {
    state.status = bad;
    return;
  }
  state.settings = edited;
  state.changed();
}

void timingSection(const PanelContext& context) {
  if (!ImGui::CollapsingHeader("Pass times", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const TimingHistory& h = *context.history;
  if (!h.module.empty()) {
    const std::vector<float> module(h.module.begin(), h.module.end());
    const std::vector<float> host(h.host.begin(), h.host.end());
    const float top = std::max(*std::max_element(host.begin(), host.end()),
                               *std::max_element(module.begin(), module.end()));
    char overlay[64];
    std::snprintf(overlay, sizeof(overlay), "module %.1f ms", module.back());
    ImGui::PlotLines("##module", module.data(), int(module.size()), 0, overlay, 0.0f, top * 1.1f,
                     ImVec2(0, 50));
    std::snprintf(overlay, sizeof(overlay), "whole frame %.1f ms", host.back());
    ImGui::PlotLines("##host", host.data(), int(host.size()), 0, overlay, 0.0f, top * 1.1f,
                     ImVec2(0, 50));
  }
  if (!context.last) return;
  // Each pass of the last frame: its time, its dispatches and its own rolling graph.
  if (ImGui::BeginTable("passes", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    for (const gi::PassTime& p : context.last->passes) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(p.name.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%8.2f ms", p.ms);
      ImGui::TableNextColumn();
      ImGui::Text("%u disp.", p.dispatches);
      ImGui::TableNextColumn();
      if (const auto found = h.passes.find(p.name); found != h.passes.end()) {
        const std::vector<float> times(found->second.begin(), found->second.end());
        ImGui::PushID(p.name.c_str());
        ImGui::PlotLines("##pass", times.data(), int(times.size()), 0, nullptr, 0.0f, FLT_MAX,
                         ImVec2(90, 14));
        ImGui::PopID();
      }
    }
    ImGui::EndTable();
  }
}

}  // namespace

void TimingHistory::add(const FrameResult& result) {
  // "gi frame" is the module's whole frame (its passes nest in it); in a split screen the right
  // half's module adds its own.
  float moduleMs = 0.0f, hostMs = 0.0f;
  for (const gi::PassTime& p : result.passes) {
    if (p.name == "host frame") hostMs = float(p.ms);
    if (p.name == "gi frame" || p.name == "gi right frame") moduleMs += float(p.ms);
  }
  module.push_back(moduleMs);
  host.push_back(hostMs);
  for (auto& [name, times] : passes) times.push_back(0.0f);
  for (const gi::PassTime& p : result.passes) {
    std::deque<float>& times = passes[p.name];
    if (times.empty()) times.assign(module.size(), 0.0f);
    times.back() += float(p.ms);
  }
  auto trim = [](std::deque<float>& d) {
    while (d.size() > kFrames) d.pop_front();
  };
  trim(module);
  trim(host);
  for (auto& [name, times] : passes) trim(times);
}

PanelRequests drawPanel(AppState& state, const PanelContext& context) {
  PanelRequests requests;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(400, ImGui::GetIO().DisplaySize.y - 16), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("vsgl_viewer");
  ImGui::TextUnformatted(context.device.c_str());
  if (context.last)
    ImGui::Text("frame %llu: %u VSGLs, panel %.0f fps",
                static_cast<unsigned long long>(context.last->frameNumber), context.last->vsglCount,
                context.uiFps);
  if (context.last && !context.last->note.empty())
    ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "%s", context.last->note.c_str());
  if (context.last && !context.last->error.empty())
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", context.last->error.c_str());
  if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
  requests.screenshot = ImGui::Button("Screenshot (F12)");
  ImGui::SameLine();
  requests.toggleRecording = ImGui::Button(context.recording ? "Stop recording" : "Record path");
  sceneSection(state);
  lightSection(state);
  viewSection(state, context);
  settingsSection(state);
  timingSection(context);
  if (context.last && !context.last->plan.empty() &&
      ImGui::CollapsingHeader("Planner", ImGuiTreeNodeFlags_DefaultOpen))
    for (const std::string& reason : context.last->plan) ImGui::TextWrapped("%s", reason.c_str());
  ImGui::End();
  return requests;
}

}  // namespace viewer
