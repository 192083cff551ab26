// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the hardware and network devices: atomic fault counters, torque dropping.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>

#include "mrh/device/device.h"

namespace mrh::device::internal {

/// DeviceCounters as atomics: bumped on the haptic (or receiving) thread, read from any.
struct AtomicCounters {
  std::atomic<std::int64_t> vendor_errors{0};
  std::atomic<std::int64_t> torque_dropped{0};
  std::atomic<std::int64_t> packets_malformed{0};
  std::atomic<std::int64_t> pose_timeouts{0};
  std::atomic<std::int64_t> poses_received{0};
  std::atomic<std::int64_t> wrenches_sent{0};

  static void Bump(std::atomic<std::int64_t>& counter) noexcept {
    counter.fetch_add(1, std::memory_order_relaxed);
  }

  DeviceCounters Load() const {
    DeviceCounters c;
    c.vendor_errors = vendor_errors.load(std::memory_order_relaxed);
    c.torque_dropped = torque_dropped.load(std::memory_order_relaxed);
    c.packets_malformed = packets_malformed.load(std::memory_order_relaxed);
    c.pose_timeouts = pose_timeouts.load(std::memory_order_relaxed);
    c.poses_received = poses_received.load(std::memory_order_relaxed);
    c.wrenches_sent = wrenches_sent.load(std::memory_order_relaxed);
    return c;
  }
};

/// A 3-DOF-output device (specs.has_torque false) cannot display torque: zero it and count the
/// tick if it was nonzero, so a rendering method's torque is never lost silently. RT-safe.
inline Wrench DropTorqueIfNoTorque(const Specifications& specs, const Wrench& w,
                                   AtomicCounters* counters) noexcept {
  if (specs.has_torque) return w;
  Wrench out = w;
  if (w.tau.squaredNorm() > 0.0) AtomicCounters::Bump(counters->torque_dropped);
  out.tau.setZero();
  return out;
}

}  // namespace mrh::device::internal
