// SPDX-License-Identifier: Apache-2.0
// DrawPanel: one ImGui window; edits go to PanelState, requests come back as PanelActions.
#include "viewer/panel.h"

#include <fmt/format.h>
#include <imgui.h>

#include "mrh/engine/method.h"
#include "viewer/method_fields.h"

namespace mrh::viewer::internal {
namespace {

// At scale 1 (pixels). The panel keeps to under a quarter of the default 1280-pixel window and,
// with its less used sections closed, to about half its height.
constexpr float kPanelWidth = 300.0f;
constexpr float kPlotHeight = 60.0f;
const ImVec4 kErrorColor(1.0f, 0.45f, 0.4f, 1.0f);

// ImGui::Text with fmt formatting (ImGui's own printf would need -Wformat exemptions).
template <typename... Args>
void Text(fmt::format_string<Args...> format, Args&&... args) {
  const std::string text = fmt::format(format, std::forward<Args>(args)...);
  ImGui::TextUnformatted(text.c_str());
}

void DrawRates(const PanelInfo& info) {
  const settings::EngineSettings& e = *info.settings;
  Text("haptic   {:7.1f} Hz  (target {:.0f}, {}{})", info.loop.rate_hz, 1.0 / e.haptic_dt,
       info.loop.fifo ? "SCHED_FIFO" : "normal priority", info.memory_locked ? ", mlockall" : "");
  Text("jitter   mean {:.0f} / p99 {:.0f} / max {:.0f} us", info.loop.jitter_mean_us,
       info.loop.jitter_p99_us, info.loop.jitter_max_us);
  Text("physics  {:7.1f} Hz  step {:.2f} ms", info.physics_hz, info.step_ms);
  Text("overruns {}  dropped ticks {}", info.loop.overruns, info.dropped_ticks);
}

// One gain field; true when an edit is finished (Enter or focus lost).
bool Gain(const char* label, double* value, double step, const char* format) {
  ImGui::InputDouble(label, value, step, 10.0 * step, format);
  return ImGui::IsItemDeactivatedAfterEdit();
}

// Method and the gains it reads (FieldsFor); a finished edit asks for a restart.
bool DrawGains(settings::EngineSettings* edit) {
  bool apply = false;
  if (ImGui::BeginCombo("method", edit->method.c_str())) {
    for (const auto& [name, summary] : engine::ListMethods()) {
      if (ImGui::Selectable(name.c_str(), name == edit->method)) {
        edit->method = name;
        apply = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", summary.c_str());
    }
    ImGui::EndCombo();
  }
  const MethodFields fields = FieldsFor(edit->method);
  settings::RenderingSettings& r = edit->rendering;
  if (fields.stiffness) {
    apply |= Gain("stiffness N/m", &r.stiffness, 100.0, "%.1f");
    apply |= Gain("damping N s/m", &r.damping, 0.5, "%.2f");
  }
  if (fields.friction) apply |= Gain("friction mu", &r.friction, 0.05, "%.2f");
  if (fields.rot_stiffness) apply |= Gain("rot. stiffness N m/rad", &r.rot_stiffness, 1.0, "%.2f");
  if (fields.coupling) {
    apply |= Gain("coupling k N/m", &r.coupling_stiffness, 100.0, "%.1f");
    apply |= Gain("coupling b N s/m", &r.coupling_damping, 1.0, "%.2f");
  }
  return apply;
}

void DrawInput(const PanelInfo& info, PanelState* state, PanelActions* actions) {
  if (state->pointer_names.size() > 1) {
    const auto chosen = static_cast<std::size_t>(state->pointer);
    const char* current = chosen < state->pointer_names.size()
                              ? state->pointer_names[chosen].c_str()
                              : state->pointer_names.front().c_str();
    if (ImGui::BeginCombo("input drives", current)) {
      for (std::size_t i = 0; i < state->pointer_names.size(); ++i) {
        if (ImGui::Selectable(state->pointer_names[i].c_str(), i == chosen) && i != chosen) {
          actions->pointer = static_cast<int>(i);
        }
      }
      ImGui::EndCombo();
    }
  }
  for (InputSource s : {InputSource::kMouse, InputSource::kSession}) {
    if (ImGui::RadioButton(InputSourceName(s), info.source == s) && info.source != s) {
      actions->source = s;
    }
    ImGui::SameLine();
  }
  ImGui::BeginDisabled(!info.replay_available);
  if (ImGui::RadioButton("replay", info.source == InputSource::kReplay)) actions->replay = true;
  ImGui::EndDisabled();
  ImGui::InputText("file", state->record_path.data(), state->record_path.size());
  if (!state->recording) {
    actions->record = ImGui::Button("Record (resets)");
  } else {
    actions->stop_record = ImGui::Button("Stop recording");
    ImGui::SameLine();
    Text("{} ticks", state->recorded_rows);
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!info.replay_available || state->recording);
  actions->replay |= ImGui::Button("Replay");
  ImGui::EndDisabled();
}

void DrawDisplay(DisplayOptions* d) {
  ImGui::Checkbox("force", &d->force);
  ImGui::SameLine();
  ImGui::Checkbox("torque", &d->torque);
  ImGui::SameLine();
  ImGui::Checkbox("proxy ghost", &d->ghost);
  ImGui::Checkbox("IR points", &d->ir_points);
  ImGui::SameLine();
  ImGui::Checkbox("IR planes", &d->ir_planes);
  ImGui::SameLine();
  ImGui::Checkbox("drag camera", &d->camera_drag);
  ImGui::SliderFloat("m per N", &d->force_scale, 0.001f, 0.1f, "%.3f",
                     ImGuiSliderFlags_Logarithmic);
  ImGui::SliderFloat("m per N m", &d->torque_scale, 0.01f, 2.0f, "%.2f",
                     ImGuiSliderFlags_Logarithmic);
  ImGui::SliderFloat("plot s", &d->plot_seconds, 1.0f, 10.0f, "%.1f");
}

void DrawHelp() {
  ImGui::TextUnformatted(
      "Pointer: left drag moves it in the view plane,\n"
      "  Shift+left drag or wheel in depth, right drag turns it,\n"
      "  arrows / PgUp / PgDn nudge it (Shift: finer).\n"
      "Camera: Ctrl+left orbit, Ctrl+right pan, Ctrl+wheel\n"
      "  or middle drag zoom (C swaps plain and Ctrl drags).\n"
      "Space pause, S step, Backspace reset, H panel, Home camera.");
}

// The session, method, rates and the latest tick's contacts and displayed wrench (torque only
// for 6-DOF methods).
void DrawStatus(const PanelInfo& info, bool torque) {
  Text("{}", info.session->file.filename().string());
  const settings::EngineSettings& running = *info.settings;
  Text("{}  physics {} ms / haptic {} ms", running.method, running.physics_dt * 1e3,
       running.haptic_dt * 1e3);
  if (torque) {
    Text("t {:.3f} s  contacts {}  |f| {:.2f} N  |tau| {:.3f} N m", info.t, info.contacts,
         info.displayed_W.f.norm(), info.displayed_W.tau.norm());
  } else {
    Text("t {:.3f} s  contacts {}  |f| {:.2f} N", info.t, info.contacts, info.displayed_W.f.norm());
  }
}

void DrawRunButtons(const PanelInfo& info, PanelActions* actions) {
  actions->toggle_pause = ImGui::Button(info.paused ? "Resume" : "Pause");
  ImGui::SameLine();
  ImGui::BeginDisabled(!info.paused);
  actions->step = ImGui::Button("Step");
  ImGui::EndDisabled();
  ImGui::SameLine();
  actions->reset = ImGui::Button("Reset");
}

// The displayed force (and, for 6-DOF methods, torque) over the last plot_seconds.
void DrawPlots(const PlotHistory& history, const DisplayOptions& display, float scale,
               bool torque) {
  const float plot_width = kPanelWidth * scale - 2.0f * ImGui::GetStyle().WindowPadding.x;
  ImGui::TextUnformatted("displayed force");
  DrawPlot("##force", history, PlotQuantity::kForce, display.plot_seconds, plot_width,
           kPlotHeight * scale);
  if (torque) {
    ImGui::TextUnformatted("displayed torque");
    DrawPlot("##torque", history, PlotQuantity::kTorque, display.plot_seconds, plot_width,
             kPlotHeight * scale);
  }
}

}  // namespace

PanelActions DrawPanel(const PanelInfo& info, PanelState* state, DisplayOptions* display,
                       const PlotHistory& history, float scale) {
  PanelActions actions;
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Once);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth * scale, 0), ImGuiCond_Once);
  ImGui::Begin("mrh view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  const bool torque = FieldsFor(info.settings->method).torque;
  DrawStatus(info, torque);
  if (ImGui::CollapsingHeader("Rates")) DrawRates(info);
  DrawRunButtons(info, &actions);
  if (ImGui::CollapsingHeader("Method and gains", ImGuiTreeNodeFlags_DefaultOpen)) {
    actions.apply = DrawGains(&state->edit);
  }
  if (ImGui::CollapsingHeader("Input and recording")) {
    DrawInput(info, state, &actions);
  }
  if (ImGui::CollapsingHeader("Show")) DrawDisplay(display);
  DrawPlots(history, *display, scale, torque);
  if (ImGui::CollapsingHeader("Help")) DrawHelp();
  if (!state->message.empty()) {
    ImGui::PushTextWrapPos(kPanelWidth * scale);
    ImGui::TextColored(kErrorColor, "%s", state->message.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
  return actions;
}

}  // namespace mrh::viewer::internal
