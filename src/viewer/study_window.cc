// SPDX-License-Identifier: Apache-2.0
// StudyWindow: the psychophysics apparatus on a GLFW window (blank stimuli, cues, key answers).
#include "mrh/viewer/study_window.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <thread>

#include "mrh/device/external.h"
#include "mrh/device/mouse.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"
#include "viewer/haptic_loop.h"
#include "viewer/window.h"

namespace mrh::viewer {
namespace internal {
namespace {

using Clock = std::chrono::steady_clock;

// Frames at most this often (Xvfb has no vsync); input is polled once per frame, and GLFW's
// sticky keys keep a press that starts and ends between two polls.
constexpr double kFramePeriod = 1.0 / 60.0;
// Cursor motion to pointer motion with --mouse (m per screen pixel).
constexpr double kMetresPerPixel = 5e-4;
// Cue text height (pixels at scale 1).
constexpr float kCueFontPixels = 40.0f;

class StudyWindow final : public psychophysics::Apparatus {
 public:
  StudyWindow(const session::Session& base, const StudyWindowSettings& settings)
      : base_(base),
        settings_(settings),
        window_(WindowSettings{
            .title = "mrh psychophysics", .width = settings.width, .height = settings.height}) {
    glfwSetInputMode(window_.handle(), GLFW_STICKY_KEYS, GLFW_TRUE);
  }

  void Cue(int interval, double pause) override {
    const Clock::time_point end = Clock::now() + Seconds(pause);
    const std::string text = "stimulus " + std::to_string(interval);
    while (Clock::now() < end && !Stopping()) Frame(text.c_str());
  }

  void Present(const session::Session& stimulus) override {
    if (Stopping()) return;
    session::Session s = stimulus;
    s.engine.mode = settings::Mode::kRealtime;
    world::World world = session::LoadWorld(s);
    const Pose X_WP0 =
        world.pointer_body() >= 0 ? world.body_state(world.pointer_body()).X_WB : Pose{};
    const Pose X_DT0 = s.device.calibration.ToDevice(X_WP0);
    std::unique_ptr<device::Device> own;
    std::unique_ptr<device::MouseDevice> mouse;
    if (settings_.mouse) {
      mouse = std::make_unique<device::MouseDevice>(X_DT0, device::MouseDeviceSettings{},
                                                    s.device.specs);
    } else {
      own = session::MakeDevice(s);
    }
    device::Device* input = mouse ? static_cast<device::Device*>(mouse.get()) : own.get();
    auto external = std::make_unique<device::ExternalDevice>(s.device.specs);
    external->Feed(input->Read(0.0));
    engine::Engine engine(std::move(world), std::move(external), s.device.calibration, s.engine);
    engine.Start();
    HapticLoop loop;
    loop.Start(&engine, input, s.engine.haptic_dt, s.engine.realtime_priority);
    const auto ticks =
        static_cast<std::int64_t>(std::llround(s.engine.duration / s.engine.haptic_dt));
    double x0 = 0.0, y0 = 0.0;
    glfwGetCursorPos(window_.handle(), &x0, &y0);
    while (loop.ticks() < ticks && !Stopping()) {
      if (mouse) FollowCursor(mouse.get(), X_DT0, x0, y0);
      Frame(nullptr);
    }
    loop.Stop();
    (void)engine.Stop();
  }

  std::optional<psychophysics::Response> Ask() override {
    (void)Pressed(GLFW_KEY_1), (void)Pressed(GLFW_KEY_2);  // drop presses made before the question
    (void)Pressed(GLFW_KEY_KP_1), (void)Pressed(GLFW_KEY_KP_2);
    const Clock::time_point start = Clock::now();
    while (!Stopping()) {
      Frame("which was heavier?  1 or 2");
      int answer = 0;
      if (Pressed(GLFW_KEY_1) || Pressed(GLFW_KEY_KP_1)) answer = 1;
      if (Pressed(GLFW_KEY_2) || Pressed(GLFW_KEY_KP_2)) answer = 2;
      if (answer != 0) {
        const std::chrono::duration<double> took = Clock::now() - start;
        return psychophysics::Response{.answer = answer, .response_time = took.count()};
      }
    }
    return std::nullopt;
  }

 private:
  static Clock::duration Seconds(double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  }

  bool Pressed(int key) { return glfwGetKey(window_.handle(), key) == GLFW_PRESS; }

  // Esc, Q or the window's close button stop the run; the state sticks.
  bool Stopping() {
    if (Pressed(GLFW_KEY_ESCAPE) || Pressed(GLFW_KEY_Q)) stop_ = true;
    return stop_ || window_.ShouldClose();
  }

  void FollowCursor(device::MouseDevice* mouse, const Pose& X_DT0, double x0, double y0) {
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_.handle(), &x, &y);
    Pose X_DT = X_DT0;
    X_DT.p += Vec3((x - x0) * kMetresPerPixel, (y0 - y) * kMetresPerPixel, 0.0);
    mouse->SetTarget(X_DT);
  }

  // A black frame, with `text` centred if given.
  void Frame(const char* text) {
    const Clock::time_point due = last_frame_ + Seconds(kFramePeriod);
    std::this_thread::sleep_until(due);
    last_frame_ = Clock::now();
    window_.BeginFrame();
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::GetBackgroundDrawList()->AddRectFilled(ImVec2(0, 0), size, IM_COL32(0, 0, 0, 255));
    if (text != nullptr) {
      const float pixels = kCueFontPixels * window_.content_scale();
      const ImVec2 extent = ImGui::GetFont()->CalcTextSizeA(pixels, 1e9f, 0.0f, text);
      ImGui::GetForegroundDrawList()->AddText(
          ImGui::GetFont(), pixels, ImVec2((size.x - extent.x) * 0.5f, (size.y - extent.y) * 0.5f),
          IM_COL32(230, 230, 230, 255), text);
    }
    ImGui::EndFrame();
    window_.RenderUi();
    window_.Swap();
  }

  session::Session base_;
  StudyWindowSettings settings_;
  Window window_;
  Clock::time_point last_frame_ = Clock::now();
  bool stop_ = false;
};

}  // namespace
}  // namespace internal

std::unique_ptr<psychophysics::Apparatus> MakeStudyWindow(const session::Session& base,
                                                          const StudyWindowSettings& settings) {
  return std::make_unique<internal::StudyWindow>(base, settings);
}

}  // namespace mrh::viewer
