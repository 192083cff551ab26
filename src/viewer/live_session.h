// SPDX-License-Identifier: Apache-2.0
// The session the viewer runs: an embedded real-time engine that restarts on reset or new gains.
#pragma once

#include <filesystem>
#include <memory>

#include "mrh/device/mouse.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"
#include "viewer/haptic_loop.h"
#include "viewer/live_feed.h"

namespace mrh::viewer::internal {

/// What drives the pointer.
enum class InputSource {
  kMouse,    ///< the viewer's MouseDevice
  kSession,  ///< the session's own device (fixed, scripted, hand, ...)
  kReplay,   ///< a recorded tick file through the replay device
};

/// "mouse", "session device", "replay".
const char* InputSourceName(InputSource source) noexcept;

/// Owns the running engine (real-time mode, embedding API), the input device and the haptic
/// loop. Live changes of gains, method or input restart the engine from the current world state,
/// so the scene carries on; Reset restarts it from the scene's initial state. UI thread only.
class LiveSession {
 public:
  /// `mouse` and `feed` must outlive this object.
  LiveSession(session::Session session, device::MouseDevice* mouse, LiveFeed* feed);
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  /// Starts the first engine from the scene's initial state. With the session's
  /// realtime_priority it first locks the process's memory (mlockall, as `mrh run --mode
  /// realtime` does; kept until this object goes), and the haptic loop asks for SCHED_FIFO.
  /// @throws mrh::InvalidArgument / mrh::SceneError as session::MakeEngine does.
  void Start(InputSource source);

  /// Restarts with `settings` and `source`, from the current world state (keep_world) or the
  /// scene's initial one. If that fails (bad settings, unreadable replay file), restarts with the
  /// previous configuration and rethrows the error.
  void Restart(const settings::EngineSettings& settings, InputSource source, bool keep_world);

  /// With several pointers, the one the input drives (the others keep their session devices);
  /// takes effect at the next Start or Restart. Out of range: the first.
  void set_driven_pointer(int i);

  int driven_pointer() const { return driven_; }

  /// The tick file kReplay plays (a ticks.csv: t, px, py, pz, qw, qx, qy, qz, world frame).
  void set_replay_file(const std::filesystem::path& file) { replay_file_ = file; }

  const session::Session& session() const { return session_; }

  const settings::EngineSettings& settings() const { return settings_; }

  InputSource source() const { return source_; }

  HapticLoop& loop() { return loop_; }

  /// True if mlockall was granted (refused without privileges, and under sanitizers).
  bool memory_locked() const { return memory_locked_; }

  /// Times the engine was (re)started.
  int starts() const { return starts_; }

  /// The viewer clock (s) at the running engine's t = 0: its ticks have t >= this.
  double time_offset() const { return time_offset_; }

 private:
  void Launch(const settings::EngineSettings& settings, InputSource source,
              const world::Snapshot* state);
  void StopEngine();
  std::unique_ptr<device::Device> MakeSource(InputSource source) const;

  session::Session session_;
  device::MouseDevice* mouse_;
  LiveFeed* feed_;
  std::filesystem::path replay_file_;

  settings::EngineSettings settings_;
  InputSource source_ = InputSource::kMouse;
  int driven_ = 0;                                ///< the pointer the input drives
  std::unique_ptr<device::Device> owned_source_;  ///< null when the source is the mouse
  std::unique_ptr<engine::Engine> engine_;
  HapticLoop loop_;
  double time_offset_ = 0.0;  ///< viewer clock at the running engine's t = 0 (s)
  int starts_ = 0;
  bool memory_locked_ = false;
};

}  // namespace mrh::viewer::internal
