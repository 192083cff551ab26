// SPDX-License-Identifier: Apache-2.0
// The haptic thread's per-tick pipeline: device → method → safety → device, plus exchange.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

#include "mrh/core/spsc_ring.h"
#include "mrh/core/triple_buffer.h"
#include "mrh/device/calibration.h"
#include "mrh/device/device.h"
#include "mrh/device/safety.h"
#include "mrh/haptic/method_haptic.h"
#include "mrh/ir/snapshot.h"
#include "mrh/ir/tick_record.h"

namespace mrh::haptic {

/// Counters the haptic thread keeps; read by other threads only after it has stopped.
struct HapticCounters {
  std::int64_t ticks = 0;
  std::int64_t periods = 0;
  double max_force = 0.0;
  double max_torque = 0.0;
  double sum_force = 0.0;  ///< Σ |displayed force| over the ticks (N), for the mean
  std::int64_t nonfinite_wrench = 0, nonfinite_device = 0;
  std::int64_t force_clamped = 0, torque_clamped = 0, watchdog_ticks = 0;
  std::int64_t dropped_tick_records = 0, dropped_reports = 0;
  Wrench last_displayed;  ///< world frame; zero once Stop() commanded the final zero wrench
  bool stopped = false;   ///< Stop() sent the final zero wrench to the device
  /// Ticks on which method status bit i (TickOutput::status) was set.
  std::array<std::int64_t, 32> method_status_ticks{};
};

/// The haptic thread's side of a run: everything one haptic tick touches. All buffers are sized in
/// the constructor; Tick() is RT-safe. Single-threaded: only the haptic thread (or the lockstep
/// loop) calls Tick().
class HapticSide {
 public:
  struct Exchange {
    TripleBuffer<ir::PhysicsSnapshot>* snapshots;  ///< physics → haptic
    SpscRing<ir::HapticReport>* reports;           ///< haptic → physics
    SpscRing<ir::TickRecord>* tick_records;        ///< haptic → recorder
    int pointer = 0;  ///< the pointer index written into this side's TickRecords
  };

  HapticSide(MethodHaptic* method, device::Device* device, const device::Calibration& calibration,
             const device::SafetySettings& safety, int ticks_per_step, double haptic_dt,
             const Exchange& exchange);

  /// Reads the device at time t once, for the initial report (setup thread).
  ir::HapticReport InitialReport(double t);

  /// One tick at time t (s since start). RT-safe.
  void Tick(double t) noexcept;

  /// Zero output from now on and sends it to the device. RT-safe.
  void Stop() noexcept;

  const HapticCounters& counters() const { return counters_; }

  /// Scales the wrench the method renders before the safety layer and the device (1: unchanged,
  /// 0: no force). Any thread, any time; Tick() picks it up at its start. Lock-free and RT-safe.
  /// @pre gain is finite and >= 0 (Engine::SetDisplayGain checks it).
  void SetDisplayGain(double gain) noexcept {
    display_gain_.store(gain, std::memory_order_relaxed);
  }

  double display_gain() const noexcept { return display_gain_.load(std::memory_order_relaxed); }

 private:
  void ReadDevice(double t) noexcept;
  void Record(double t, const TickOutput& out, const Wrench& displayed,
              std::uint32_t safety_bits) noexcept;
  void EndPeriod(double t) noexcept;
  void Count(const Wrench& displayed, std::uint32_t bits) noexcept;

  MethodHaptic* method_;
  device::Device* device_;
  device::Calibration calibration_;
  device::SafetyFilter safety_;
  int n_;
  double dt_;
  Exchange exchange_;

  Pose X_WP_;
  Twist V_WP_;
  bool device_ok_ = true;
  int j_ = 0;
  int ticks_in_period_ = 0;
  double last_adopt_t_ = 0.0;
  ir::HapticReport report_;
  HapticCounters counters_;
  // A single value: relaxed order suffices, as no other data is published with it.
  std::atomic<double> display_gain_{1.0};
  static_assert(std::atomic<double>::is_always_lock_free);
};

}  // namespace mrh::haptic
