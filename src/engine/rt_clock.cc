// SPDX-License-Identifier: Apache-2.0
// Real-time helpers over POSIX: clock, sleeping, scheduling class and memory locking.
#include "mrh/engine/rt_clock.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>

namespace mrh::engine {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

timespec ToTimespec(std::int64_t ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / kNsPerS);
  ts.tv_nsec = static_cast<long>(ns % kNsPerS);
  return ts;
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kUnderSanitizer = true;
#else
constexpr bool kUnderSanitizer = false;
#endif

}  // namespace

std::int64_t NowNs() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

void SleepUntilNs(std::int64_t deadline_ns, std::int64_t spin_ns) noexcept {
  const std::int64_t wake = deadline_ns - spin_ns;
  if (NowNs() < wake) {
    const timespec ts = ToTimespec(wake);
    // EINTR only shortens the sleep; the spin below still ends at the deadline.
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  while (NowNs() < deadline_ns) {
  }
}

PeriodicDeadline::PeriodicDeadline(std::int64_t period_ns) noexcept
    : period_ns_(period_ns),
      start_ns_(NowNs()),
      deadline_ns_(start_ns_),
      last_wake_ns_(start_ns_) {}

PeriodicDeadline::Wake PeriodicDeadline::Next() noexcept {
  deadline_ns_ += period_ns_;
  SleepUntilNs(deadline_ns_, kDeadlineSpinNs);
  Wake wake;
  wake.now_ns = NowNs();
  wake.overrun = wake.now_ns - deadline_ns_ > period_ns_;
  if (wake.overrun) deadline_ns_ = wake.now_ns;
  wake.deadline_ns = deadline_ns_;
  wake.period_error_us =
      std::abs(static_cast<double>(wake.now_ns - last_wake_ns_ - period_ns_)) * 1e-3;
  last_wake_ns_ = wake.now_ns;
  return wake;
}

bool RequestFifoPriority(int priority, std::string* why) {
  sched_param param{};
  param.sched_priority = priority;
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (rc != 0) {
    *why = std::string("SCHED_FIFO refused: ") + std::strerror(rc);
    return false;
  }
  return true;
}

bool LockAllMemory(std::string* why) {
  if (kUnderSanitizer) {
    *why = "mlockall skipped under a sanitizer build";
    return false;
  }
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    *why = std::string("mlockall refused: ") + std::strerror(errno);
    return false;
  }
  return true;
}

void UnlockAllMemory() noexcept {
  munlockall();
}

}  // namespace mrh::engine
