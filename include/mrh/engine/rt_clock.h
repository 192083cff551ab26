// SPDX-License-Identifier: Apache-2.0
// Real-time helpers: monotonic clock, absolute-deadline sleep, SCHED_FIFO and mlockall requests.
// The engine's real-time mode uses them, and so can any loop that ticks Engine::Tick itself
// (the embedding API, the viewer), to keep its period the same way.
#pragma once

#include <cstdint>
#include <string>

namespace mrh::engine {

/// SCHED_FIFO priority of the engine's haptic thread: above the physics and UI threads, which
/// stay at normal priority.
inline constexpr int kHapticFifoPriority = 80;

/// How long before a deadline SleepUntilNs stops sleeping and starts spinning (ns): the kernel
/// alone wakes 50–110 µs late on the project's VM (docs/realtime.md).
inline constexpr std::int64_t kDeadlineSpinNs = 150'000;

/// CLOCK_MONOTONIC in nanoseconds. RT-safe.
std::int64_t NowNs() noexcept;

/// Sleeps until the absolute CLOCK_MONOTONIC deadline (ns): clock_nanosleep(TIMER_ABSTIME) to
/// `spin_ns` before it, then spins. Returns at once if the deadline has passed. RT-safe.
void SleepUntilNs(std::int64_t deadline_ns, std::int64_t spin_ns = kDeadlineSpinNs) noexcept;

/// The one deadline loop of the haptic rate (the engine's real-time mode, the viewer's haptic
/// thread): absolute deadlines every `period_ns` from the start, and on an overrun (a wake more
/// than one period late) the deadline moves to the wake time, so missed periods are skipped
/// instead of burst through (catching up would run ticks back to back, each assuming a full period
/// had passed). RT-safe; owned by one thread.
class PeriodicDeadline {
 public:
  struct Wake {
    std::int64_t now_ns = 0;       ///< CLOCK_MONOTONIC at the wake
    std::int64_t deadline_ns = 0;  ///< the deadline this wake serves (moved on an overrun)
    double period_error_us = 0.0;  ///< |time since the previous wake − period| (µs)
    bool overrun = false;
  };

  /// Starts the first period now. `period_ns` > 0.
  explicit PeriodicDeadline(std::int64_t period_ns) noexcept;

  /// Sleeps to the next deadline (SleepUntilNs with kDeadlineSpinNs) and reports the wake.
  Wake Next() noexcept;

  std::int64_t start_ns() const noexcept { return start_ns_; }

 private:
  std::int64_t period_ns_;
  std::int64_t start_ns_;
  std::int64_t deadline_ns_;
  std::int64_t last_wake_ns_;
};

/// Gives the calling thread SCHED_FIFO at `priority`. Returns false with the reason in *why
/// (typically: no CAP_SYS_NICE). Not RT-safe (it may allocate the message).
bool RequestFifoPriority(int priority, std::string* why);

/// mlockall(MCL_CURRENT | MCL_FUTURE), so that page faults do not stall the haptic thread.
/// Returns false with the reason in *why (also under sanitizers, whose shadow memory must not be
/// locked). Process-wide. Not RT-safe.
bool LockAllMemory(std::string* why);

/// Undoes LockAllMemory (munlockall). Process-wide.
void UnlockAllMemory() noexcept;

}  // namespace mrh::engine
