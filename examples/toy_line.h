// SPDX-License-Identifier: Apache-2.0
// The worked example of docs/architecture.md, "Adding a device": "toy-line" moves its grip along
// a straight line. examples/toy_method.cc runs it with the toy method of toy_plane.h.
#pragma once

#include <algorithm>
#include <memory>

#include "mrh/core/spatial.h"
#include "mrh/device/device.h"
#include "mrh/session/devices.h"

namespace toy {

/// Moves the grip from `from` to `to` (m, device frame, identity orientation) at constant speed
/// over `duration` s (> 0), then holds it. Displays nothing: it only remembers the largest force
/// it was told to display. Read and SetWrench are RT-safe (no allocation, lock, throw or I/O).
class LineDevice final : public mrh::device::Device {
 public:
  LineDevice(const mrh::Vec3& from, const mrh::Vec3& to, double duration,
             const mrh::device::Specifications& specs)
      : specs_(specs), from_(from), to_(to), duration_(duration) {}

  const mrh::device::Specifications& specifications() const override { return specs_; }

  mrh::device::DeviceState Read(double t) noexcept override {
    const double s = std::clamp(t / duration_, 0.0, 1.0);
    mrh::device::DeviceState state;
    state.t = t;
    state.X_DT = mrh::Pose{from_ + s * (to_ - from_), mrh::Quat::Identity()};
    if (t < duration_) state.V_DT.v = (to_ - from_) / duration_;
    return state;
  }

  void SetWrench(const mrh::Wrench& w_D) noexcept override {
    max_force_ = std::max(max_force_, w_D.f.norm());
  }

  double max_force() const { return max_force_; }

 private:
  mrh::device::Specifications specs_;
  mrh::Vec3 from_, to_;
  double duration_;
  double max_force_ = 0.0;
};

/// Registers device type "toy-line" (call once before LoadSession: the parser checks
/// device.type): the grip slides 0.1 m along +x over the session's duration, with the device
/// block's limits.
inline void RegisterToyLine() {
  mrh::session::RegisterDevice(
      {"toy-line", "Example: the grip slides 0.1 m along +x over the run",
       [](const mrh::session::DeviceSource& s) -> std::unique_ptr<mrh::device::Device> {
         return std::make_unique<LineDevice>(mrh::Vec3::Zero(), mrh::Vec3(0.1, 0.0, 0.0),
                                             s.session.engine.duration, s.config.specs);
       }});
}

}  // namespace toy
