// SPDX-License-Identifier: Apache-2.0
// A one-line progress bar on stderr for runs long enough to need one.
#pragma once

#include <chrono>
#include <cstddef>

namespace mrh::cli {

/// When and how the bar is shown.
struct ProgressSettings {
  bool enabled = false;   ///< stderr is a TTY or --progress was given, and not --quiet
  bool realtime = false;  ///< real time: the run lasts `duration` of wall time
  double duration = 0.0;  ///< s, the run's configured duration
};

/// Draws `[#####.....]  42%  t=4.2/10.0 s`, at most 10 times a second, only for runs that take
/// more than ~2 s of wall time (known up front in real time; in lockstep, once 2 s have passed).
class ProgressBar {
 public:
  explicit ProgressBar(const ProgressSettings& settings);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// `fraction` of the run is done, in [0, 1].
  void Update(double fraction);
  /// Clears the line if anything was drawn.
  void Finish();

 private:
  using Clock = std::chrono::steady_clock;
  ProgressSettings settings_;
  Clock::time_point start_;
  Clock::time_point last_draw_;
  std::size_t drawn_chars_ = 0;
};

}  // namespace mrh::cli
