// SPDX-License-Identifier: Apache-2.0
// RunViewer: the frame loop tying the window, the live session, the overlay and the panel.
#include "mrh/viewer/viewer.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <thread>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/device/mouse.h"
#include "mrh/world/scene_renderer.h"
#include "mrh/world/world.h"
#include "viewer/live_feed.h"
#include "viewer/live_session.h"
#include "viewer/overlay.h"
#include "viewer/panel.h"
#include "viewer/plot.h"
#include "viewer/pointer_choice.h"
#include "viewer/pointer_control.h"
#include "viewer/tick_file.h"
#include "viewer/window.h"

namespace mrh::viewer {
namespace internal {
namespace {

// Ticks the feed holds between frames: 30 s at 1 kHz, far more than a stalled frame needs.
constexpr std::size_t kFeedTicks = std::size_t{1} << 15;
// Ticks the plots keep: 10 s at 1 kHz, the longest plot window.
constexpr std::size_t kPlotTicks = 10'000;

// The initial camera frames the moving bodies and the pointer (MuJoCo's default frames the whole
// model, where a large floor makes the objects small), slightly from the side and above.
constexpr double kFrameAzimuthDeg = 120.0;
constexpr double kFrameElevationDeg = -25.0;

// The pointers' initial poses and bodies, and the initial scene, from the session's world.
struct InitialView {
  std::vector<Pose> X_WP;         // per pointer, in session order
  std::vector<int> pointer_body;  // per pointer
  world::SceneState state;
  std::vector<int> framed_bodies;  // moving bodies and the pointer
  world::OrbitCamera camera;       // set once the renderer has framed them
};

InitialView LoadInitialView(const session::Session& session) {
  const world::World world = session::LoadWorld(session);
  InitialView view;
  const std::vector<std::string> names = PointerNames(session);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int body = i == 0 ? world.pointer_body() : world.FindBody(names[i]);
    view.pointer_body.push_back(body);
    view.X_WP.push_back(body >= 0 ? world.body_state(body).X_WB : Pose{});
  }
  world::CaptureSceneState(world, &view.state);
  for (int b = 0; b < world.num_bodies(); ++b) {
    const bool pointer =
        std::find(view.pointer_body.begin(), view.pointer_body.end(), b) != view.pointer_body.end();
    if (!world.body(b).is_static || pointer) view.framed_bodies.push_back(b);
  }
  return view;
}

std::string DefaultRecordPath(const session::Session& session) {
  return (std::filesystem::path("out") / (session.file.stem().string() + "-view") / "ticks.csv")
      .string();
}

class ViewerApp {
 public:
  ViewerApp(const session::Session& session, const ViewerSettings& settings)
      : settings_(settings),
        session_(session),
        window_(WindowSettings{.title = "mrh view - " + session.file.filename().string(),
                               .width = settings.width,
                               .height = settings.height,
                               .visible = !headless(),
                               .input = !headless(),
                               .install_callbacks = headless() ? nullptr : &PointerControl::Install,
                               .callback_data = &control_}),
        renderer_(session.scene, world::SceneRendererSettings{.font_scale = static_cast<int>(
                                                                  100 * window_.content_scale())}),
        feed_(kFeedTicks),
        initial_(LoadInitialView(session)),
        pointer_body_(initial_.pointer_body.front()),
        target_W_(initial_.X_WP.front()),
        poses_(initial_.X_WP),
        mouse_(session.device.calibration.ToDevice(target_W_), device::MouseDeviceSettings{},
               session.device.specs),
        live_(session, &mouse_, &feed_),
        history_(kPlotTicks) {
    renderer_.Update(initial_.state);
    renderer_.camera().azimuth_deg = kFrameAzimuthDeg;
    renderer_.camera().elevation_deg = kFrameElevationDeg;
    renderer_.FrameBodies(initial_.framed_bodies);
    initial_.camera = renderer_.camera();
    display_.panel = settings.panel;
    panel_.edit = live_.settings();
    panel_.pointer_names = PointerNames(session);
    const std::string path = DefaultRecordPath(session);
    std::strncpy(panel_.record_path.data(), path.c_str(), panel_.record_path.size() - 1);
    last_.X_WP = target_W_;
    last_.X_WQ = target_W_;  // no proxy (and no ghost) before the first tick
    // Ticks 0 .. N run (t = 0 .. at), then the loop holds: set before the loop starts.
    if (settings.at >= 0.0) {
      live_.loop().HoldAtTick(std::llround(settings.at / session.engine.haptic_dt) + 1);
    }
    live_.Start(headless() ? InputSource::kSession : InputSource::kMouse);
    rate_start_ = Clock::now();
  }

  double Run() {
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(1.0 / settings_.frame_rate_hz));
    Clock::time_point due = Clock::now();
    for (int frame = 0; !window_.ShouldClose(); ++frame) {
      const bool last =
          settings_.at >= 0.0 ? Settled() : headless() && frame + 1 == settings_.frames;
      Frame(last);
      if (last) break;
      // At most frame_rate_hz even without vsync (Xvfb has none); a slow frame is not made up.
      due = std::max(due + period, Clock::now());
      std::this_thread::sleep_until(due);
    }
    return last_.t;
  }

 private:
  using Clock = std::chrono::steady_clock;

  bool headless() const { return settings_.frames > 0 || settings_.at >= 0.0; }

  // With `at`: true once the haptic loop holds, its last tick is drawn and the physics side has
  // delivered no new step for kSettleFrames frames (it finishes the step in progress, which
  // takes milliseconds; a frame is ~17 ms).
  bool Settled() {
    constexpr int kSettleFrames = 3;
    if (!live_.loop().holding() || feed_.steps() != settle_steps_ ||
        last_.t < settings_.at - 0.5 * session_.engine.haptic_dt) {
      settle_steps_ = feed_.steps();
      settle_frames_ = 0;
      return false;
    }
    return ++settle_frames_ > kSettleFrames;
  }

  void Frame(bool last) {
    window_.BeginFrame();
    KeyActions keys;
    if (!headless()) {
      keys = control_.Process(window_.handle(), renderer_, display_.camera_drag, &target_W_);
      FeedMouse();
    }
    DrainTicks();
    DrawScene();
    int width = 0, height = 0;
    window_.FramebufferSize(&width, &height);
    if (width > 0 && height > 0) renderer_.Render(width, height);  // 0 while minimized
    PanelActions actions;
    if (display_.panel)
      actions = DrawPanel(Info(), &panel_, &display_, history_, window_.content_scale());
    window_.RenderUi();
    if (last && !settings_.screenshot.empty() && width > 0 && height > 0) {
      WritePng(settings_.screenshot, width, height, renderer_.ReadPixels(width, height));
    }
    window_.Swap();
    Handle(actions, keys);
  }

  // The target stays inside the device's workspace so that it never runs away from the tool.
  void FeedMouse() {
    const device::Calibration& c = PointerDevice(session_, live_.driven_pointer()).calibration;
    Pose X_DT = c.ToDevice(target_W_);
    const device::Specifications& specs = mouse_.specifications();
    X_DT.p = X_DT.p.cwiseMax(specs.workspace_min).cwiseMin(specs.workspace_max);
    target_W_ = c.ToWorld(X_DT);
    if (live_.source() == InputSource::kMouse) mouse_.SetTarget(X_DT);
  }

  void DrainTicks() {
    TickSample sample;
    while (feed_.PopTick(&sample)) {
      const auto i = static_cast<std::size_t>(sample.pointer);
      if (i < poses_.size()) poses_[i] = sample.X_WP;
      // Plots, the panel and recordings follow the pointer the mouse drives.
      if (sample.pointer != live_.driven_pointer()) continue;
      history_.Push(sample);
      last_ = sample;
      if (recording_ && sample.t >= record_from_) recording_->Write(sample);
    }
    if (recording_) panel_.recorded_rows = recording_->rows();
    // Other inputs move the pointer: the mouse takes over from where it is.
    if (live_.source() != InputSource::kMouse) target_W_ = last_.X_WP;
  }

  void DrawScene() {
    feed_.UpdateScene();
    feed_.UpdateIr();
    state_ = feed_.scene();
    // Every pointer is drawn at its newest tick's pose (1 kHz), not the last physics step's.
    for (auto& [body, X_WB] : state_.mocap) {
      for (std::size_t i = 0; i < poses_.size(); ++i) {
        if (body == initial_.pointer_body[i]) X_WB = poses_[i];
      }
    }
    renderer_.Update(state_);
    DrawOverlay(renderer_, last_, feed_.ir(), display_, pointer_body_);
  }

  PanelInfo Info() {
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - rate_start_).count();
    if (elapsed >= 1.0) {
      physics_hz_ = static_cast<double>(feed_.steps() - rate_steps_) / elapsed;
      rate_steps_ = feed_.steps();
      rate_start_ = now;
    }
    PanelInfo info;
    info.session = &live_.session();
    info.settings = &live_.settings();
    info.loop = live_.loop().ReadStats();
    info.memory_locked = live_.memory_locked();
    info.source = live_.source();
    info.paused = live_.loop().paused();
    info.physics_hz = physics_hz_;
    info.step_ms = feed_.step_ms();
    info.dropped_ticks = feed_.dropped_ticks();
    info.t = last_.t;
    info.contacts = last_.contacts;
    info.displayed_W = last_.displayed_W;
    info.replay_available = std::filesystem::is_regular_file(panel_.record_path.data());
    return info;
  }

  void Handle(const PanelActions& a, const KeyActions& k) {
    HapticLoop& loop = live_.loop();
    if (a.toggle_pause || k.toggle_pause) loop.set_paused(!loop.paused());
    if ((a.step || k.step) && loop.paused()) loop.StepTicks(live_.settings().ticks_per_step());
    if (k.toggle_panel) display_.panel = !display_.panel;
    if (k.toggle_camera) display_.camera_drag = !display_.camera_drag;
    if (k.reset_camera) renderer_.camera() = initial_.camera;
    if (a.stop_record || ((a.record || a.replay) && recording_)) StopRecording();
    if (a.reset || k.reset) Restart(live_.settings(), live_.source(), false);
    if (a.apply) Restart(panel_.edit, live_.source(), true);
    if (a.source) {
      if (*a.source == InputSource::kMouse) TeleportMouse(last_.X_WP);
      Restart(live_.settings(), *a.source, true);
    }
    if (a.pointer) SelectPointer(*a.pointer);
    if (a.record) StartRecording();
    if (a.replay) {
      live_.set_replay_file(panel_.record_path.data());
      Restart(live_.settings(), InputSource::kReplay, false);
    }
  }

  void TeleportMouse(const Pose& X_WP) {
    target_W_ = X_WP;
    const device::Calibration& c = PointerDevice(session_, live_.driven_pointer()).calibration;
    mouse_.Teleport(c.ToDevice(target_W_));
  }

  // The mouse takes over the chosen pointer where it is; the one it leaves goes back to its own
  // session device.
  void SelectPointer(int i) {
    live_.set_driven_pointer(i);
    panel_.pointer = live_.driven_pointer();
    pointer_body_ = initial_.pointer_body[static_cast<std::size_t>(panel_.pointer)];
    TeleportMouse(poses_[static_cast<std::size_t>(panel_.pointer)]);
    history_.Clear();
    Restart(live_.settings(), live_.source(), true);
  }

  void Restart(const settings::EngineSettings& settings, InputSource source, bool keep_world) {
    try {
      live_.Restart(settings, source, keep_world);
      panel_.message.clear();
    } catch (const Error& e) {
      panel_.message = e.what();
    }
    panel_.edit = live_.settings();
  }

  // Recording starts from a reset so that replaying the file reproduces the run.
  void StartRecording() {
    try {
      recording_.emplace(panel_.record_path.data());
    } catch (const Error& e) {
      panel_.message = e.what();
      return;
    }
    Restart(live_.settings(), live_.source(), false);
    record_from_ = live_.time_offset();
    panel_.recording = true;
  }

  void StopRecording() {
    if (!recording_) return;
    try {
      recording_->Close();
      panel_.message =
          fmt::format("recorded {} ticks to {}", recording_->rows(), recording_->path().string());
    } catch (const Error& e) {
      panel_.message = e.what();
    }
    recording_.reset();
    panel_.recording = false;
  }

  ViewerSettings settings_;
  session::Session session_;
  PointerControl control_;
  Window window_;
  world::SceneRenderer renderer_;
  LiveFeed feed_;
  InitialView initial_;
  int pointer_body_ = -1;
  Pose target_W_;            // the pointer target the mouse drives (world frame)
  std::vector<Pose> poses_;  // every pointer's newest tick pose (world frame)
  device::MouseDevice mouse_;
  LiveSession live_;  // after feed_ and mouse_: its threads stop before they go
  PlotHistory history_;
  PanelState panel_;
  DisplayOptions display_;
  TickSample last_;
  world::SceneState state_;
  std::optional<TickFile> recording_;
  double record_from_ = 0.0;
  Clock::time_point rate_start_;
  std::int64_t settle_steps_ = -1;
  int settle_frames_ = 0;
  std::int64_t rate_steps_ = 0;
  double physics_hz_ = 0.0;
};

}  // namespace
}  // namespace internal

double RunViewer(const session::Session& session, const ViewerSettings& settings) {
  internal::ViewerApp app(session, settings);
  return app.Run();
}

}  // namespace mrh::viewer
