// SPDX-License-Identifier: Apache-2.0
// The Dear ImGui panel: rates, gains, pause/step/reset, input source, recording, plots.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mrh/session/session.h"
#include "mrh/settings/settings.h"
#include "viewer/haptic_loop.h"
#include "viewer/live_session.h"
#include "viewer/overlay.h"
#include "viewer/plot.h"

namespace mrh::viewer::internal {

/// What the panel edits and remembers between frames.
struct PanelState {
  settings::EngineSettings edit;  ///< method and gains being edited
  std::array<char, 512> record_path{};
  bool recording = false;
  std::int64_t recorded_rows = 0;
  std::string message;  ///< the last error or notice, shown in the panel
  /// The session's pointers (bodies, in order); with two or more the panel offers a choice of
  /// the one the input drives.
  std::vector<std::string> pointer_names;
  int pointer = 0;  ///< the pointer the input drives
};

/// What the panel shows this frame.
struct PanelInfo {
  const session::Session* session = nullptr;
  /// The running engine's settings (method and gains as applied, which differ from the
  /// session file's after an edit).
  const settings::EngineSettings* settings = nullptr;
  LoopStats loop;
  bool memory_locked = false;  ///< mlockall granted
  InputSource source = InputSource::kMouse;
  bool paused = false;
  double physics_hz = 0.0;  ///< physics steps per wall second (last second)
  double step_ms = 0.0;     ///< wall time of the last physics step
  std::int64_t dropped_ticks = 0;
  double t = 0.0;  ///< s, viewer clock of the newest tick
  int contacts = 0;
  Wrench displayed_W;             ///< newest displayed wrench
  bool replay_available = false;  ///< the record file exists
};

/// What the user asked for this frame.
struct PanelActions {
  bool toggle_pause = false;
  bool step = false;
  bool reset = false;
  bool apply = false;                 ///< restart with PanelState::edit
  std::optional<InputSource> source;  ///< switch input (restart)
  bool record = false;                ///< reset and start recording to record_path
  bool stop_record = false;
  bool replay = false;         ///< reset and play record_path
  std::optional<int> pointer;  ///< drive this pointer instead (restart)
};

/// Draws the panel (a window docked at the left, `scale` = the display's content scale).
PanelActions DrawPanel(const PanelInfo& info, PanelState* state, DisplayOptions* display,
                       const PlotHistory& history, float scale);

}  // namespace mrh::viewer::internal
