// SPDX-License-Identifier: Apache-2.0
// Real-time helpers: monotonic clock, absolute-deadline sleep, SCHED_FIFO and mlockall requests.
#pragma once

#include <cstdint>
#include <string>

namespace mrh::engine::internal {

/// CLOCK_MONOTONIC in nanoseconds. RT-safe.
std::int64_t NowNs() noexcept;

/// Sleeps until the absolute CLOCK_MONOTONIC deadline: clock_nanosleep(TIMER_ABSTIME) to
/// `spin_ns` before it, then spins (the kernel alone wakes 50–110 µs late here). RT-safe.
void SleepUntilNs(std::int64_t deadline_ns, std::int64_t spin_ns) noexcept;

/// Gives the calling thread SCHED_FIFO at `priority`. Returns false with the reason in *why.
bool RequestFifoPriority(int priority, std::string* why);

/// mlockall(MCL_CURRENT | MCL_FUTURE). Returns false with the reason in *why (also under
/// sanitizers, whose shadow memory must not be locked).
bool LockAllMemory(std::string* why);

/// Undoes LockAllMemory.
void UnlockAllMemory() noexcept;

}  // namespace mrh::engine::internal
