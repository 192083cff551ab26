// SPDX-License-Identifier: Apache-2.0
// The haptic tick: adopt the newest snapshot, render, shape for safety, command, record.
#include "mrh/haptic/haptic_side.h"

#include <algorithm>

namespace mrh::haptic {

HapticSide::HapticSide(MethodHaptic* method, device::Device* device,
                       const device::Calibration& calibration, const device::SafetySettings& safety,
                       int ticks_per_step, double haptic_dt, const Exchange& exchange)
    : method_(method),
      device_(device),
      calibration_(calibration),
      safety_(device->specifications(), safety),
      n_(ticks_per_step),
      dt_(haptic_dt),
      exchange_(exchange) {}

ir::HapticReport HapticSide::InitialReport(double t) {
  ReadDevice(t);
  ir::HapticReport report;
  report.t = t;
  report.X_WP = X_WP_;
  report.V_WP = V_WP_;
  return report;
}

void HapticSide::ReadDevice(double t) noexcept {
  const device::DeviceState state = device_->Read(t);
  device_ok_ = IsFinite(state.X_DT) && IsFinite(state.V_DT) && state.X_DT.q.norm() > 0.5;
  if (!device_ok_) {
    // Keep the last good pose: NaN never reaches the method (and the safety layer zeroes the
    // output for this tick).
    V_WP_ = Twist{};
    return;
  }
  Pose X_DT = state.X_DT;
  X_DT.q.normalize();
  X_WP_ = calibration_.ToWorld(X_DT);
  V_WP_ = calibration_.ToWorld(state.V_DT);
}

void HapticSide::Tick(double t) noexcept {
  const double gain = display_gain_.load(std::memory_order_relaxed);
  ReadDevice(t);
  if (exchange_.snapshots->Update()) {
    method_->Adopt(exchange_.snapshots->read_slot());
    j_ = 0;
    last_adopt_t_ = t;
  }
  TickInput in;
  in.tick = counters_.ticks;
  in.t = t;
  in.j = j_;
  in.n = n_;
  in.dt = dt_;
  in.X_WP = X_WP_;
  in.V_WP = V_WP_;
  TickOutput out;
  out.X_WQ = X_WP_;
  method_->HapticTick(in, &out);
  // A non-finite proxy (after bad input) never reaches the records: the pointer stands in.
  if (!IsFinite(out.X_WQ)) out.X_WQ = X_WP_;

  std::uint32_t bits = 0;
  // The gain scales what the user feels only: the method's reaction on the objects and the
  // recorded rendered wrench stay as rendered; the safety layer still clamps the scaled wrench.
  const Wrench scaled{out.w_W.f * gain, out.w_W.tau * gain};
  const Wrench displayed = safety_.Apply(scaled, t, t - last_adopt_t_, device_ok_, &bits);
  device_->SetSafetyBits(bits);
  device_->SetWrench(calibration_.ToDevice(displayed));
  Count(displayed, bits);

  Record(t, out, displayed, bits);

  ++counters_.ticks;
  ++j_;
  if (++ticks_in_period_ == n_) EndPeriod(t);
}

// The tick's record for the physics thread (dropped, and counted, when its ring is full) and the
// method's status bits counted per bit.
void HapticSide::Record(double t, const TickOutput& out, const Wrench& displayed,
                        std::uint32_t safety_bits) noexcept {
  ir::TickRecord record;
  record.tick = counters_.ticks;
  record.pointer = exchange_.pointer;
  record.t = t;
  record.X_WP = X_WP_;
  record.X_WQ = out.X_WQ;
  record.displayed_W = displayed;
  record.rendered_W = out.w_W;
  record.contacts = out.contacts;
  record.safety_bits = safety_bits;
  record.method_status = out.status;
  for (std::uint32_t s = out.status, i = 0; s != 0; s >>= 1, ++i) {
    if (s & 1u) ++counters_.method_status_ticks[i];
  }
  if (!exchange_.tick_records->TryPush(record)) ++counters_.dropped_tick_records;
}

void HapticSide::EndPeriod(double t) noexcept {
  report_.period = counters_.periods++;
  report_.ticks = ticks_in_period_;
  report_.t = t;
  report_.X_WP = X_WP_;
  report_.V_WP = V_WP_;
  report_.status = ir::kStatusOk;
  report_.impulses.Clear();
  method_->EndPeriod(&report_);
  if (!exchange_.reports->TryPush(report_)) ++counters_.dropped_reports;
  ticks_in_period_ = 0;
}

void HapticSide::Count(const Wrench& displayed, std::uint32_t bits) noexcept {
  counters_.last_displayed = displayed;
  counters_.max_force = std::max(counters_.max_force, displayed.f.norm());
  counters_.sum_force += displayed.f.norm();
  counters_.max_torque = std::max(counters_.max_torque, displayed.tau.norm());
  if (bits & device::kSafetyNonFiniteWrench) ++counters_.nonfinite_wrench;
  if (bits & device::kSafetyNonFiniteDevice) ++counters_.nonfinite_device;
  if (bits & device::kSafetyForceClamped) ++counters_.force_clamped;
  if (bits & device::kSafetyTorqueClamped) ++counters_.torque_clamped;
  if (bits & device::kSafetyWatchdog) ++counters_.watchdog_ticks;
}

void HapticSide::Stop() noexcept {
  safety_.Stop();
  device_->SetWrench(Wrench{});
  counters_.last_displayed = Wrench{};
  counters_.stopped = true;
}

}  // namespace mrh::haptic
