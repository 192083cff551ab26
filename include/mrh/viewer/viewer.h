// SPDX-License-Identifier: Apache-2.0
// The interactive viewer (`mrh view`): a session in real time in a window, driven by the mouse.
#pragma once

#include <filesystem>

#include "mrh/session/session.h"

namespace mrh::viewer {

/// How the viewer runs.
struct ViewerSettings {
  /// > 0: headless use. Render this many frames, driving the pointer with the session's own
  /// device (no mouse, no keyboard), then return. The session runs in real time while frames
  /// draw, so the simulated time of the last frame is about frames / frame_rate_hz seconds, or
  /// later when frames take longer to draw: use `at` to aim at a moment. 0: interactive until
  /// the window is closed (unless `at` is set).
  int frames = 0;
  /// >= 0: headless use at a simulated time (s). The session's own device drives the pointer;
  /// the haptic loop stops after its tick at `at` (rounded to the haptic period), the physics
  /// side finishes the step in progress, and one frame of that state is drawn, then return.
  /// The bodies drawn are those the haptic thread renders against at `at` (the physics step
  /// ahead of it, by the timing rule in docs/architecture.md). Exclusive with frames. < 0: unused.
  double at = -1.0;
  /// With frames > 0 or at >= 0 (optional): write the last frame here as a PNG.
  std::filesystem::path screenshot;
  /// Draw the ImGui panel (rates, gains, controls, plots).
  bool panel = true;
  int width = 1280;  ///< initial window size (screen coordinates)
  int height = 800;
  /// Frames are drawn at this rate at most (Hz, > 0): headless frame N shows the session about
  /// N / rate seconds in, or later when frames take longer to draw.
  double frame_rate_hz = 60.0;
};

/// Opens a window on the current X display, runs `session` in real-time mode (its method, gains
/// and rates; the pointer driven by a mouse device, or by the session's device when headless)
/// and draws it with MuJoCo's renderer until the window closes or `frames` are done. Runs on
/// the calling thread, plus the engine's physics thread and the viewer's haptic thread.
/// @throws mrh::RuntimeError when there is no display (the message suggests xvfb-run and
/// `mrh run`), no usable OpenGL, or the screenshot cannot be written; mrh::InvalidArgument or
/// mrh::SceneError as session::MakeEngine does. Not RT-safe.
/// @return the simulated time of the newest haptic tick in the last frame drawn (s).
double RunViewer(const session::Session& session, const ViewerSettings& settings);

}  // namespace mrh::viewer
