// SPDX-License-Identifier: Apache-2.0
// The hand device: a simulated user whose mass-spring-damper hand follows a scripted target and
// is pushed by the displayed wrench (closed loop).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "device/track_impl.h"
#include "mrh/core/error.h"
#include "mrh/core/spatial.h"
#include "mrh/core/validate.h"
#include "mrh/device/simulated.h"

namespace mrh::device {
namespace {

// Largest integration step (s). With the defaults the fastest mode is the rotation,
// sqrt(rot_stiffness / inertia) = 63 rad/s; a 2 kN/m wall on the 0.5 kg hand is also 63 rad/s.
// omega * h = 0.06 is far inside semi-implicit Euler's stability bound omega * h < 2.
constexpr double kMaxStep = 1e-3;
// Bounded catch-up: a longer gap between reads (a paused session) is integrated over its last
// kMaxSteps * kMaxStep = 1 s only, as if the hand had waited.
constexpr double kMaxSteps = 1000.0;
// Absorbs rounding in span / kMaxStep so a 1 ms tick is one step, not two.
constexpr double kStepCountSlack = 1e-9;

// Documented ranges (docs/session-format.md, "Ranges"). The rate limits keep the 1 ms
// semi-implicit Euler step stable and accurate: omega * h <= 1 and (d / m) * h <= 1.
constexpr double kMaxStiffnessPerMass = 1.0 / (kMaxStep * kMaxStep);  // 1/s^2
constexpr double kMaxDampingPerMass = 1.0 / kMaxStep;                 // 1/s

// `gain` / `mass` (a spring or damper over its mass or inertia) must be at most `limit`.
void RequireRate(double gain, double mass, double limit, const char* gain_key,
                 const char* mass_key) {
  if (gain / mass <= limit) return;
  throw InvalidArgument(std::string(gain_key) + " = " + FormatNumber(gain) + " with " + mass_key +
                        " = " + FormatNumber(mass) + " makes the simulated hand unstable at its " +
                        "1 ms step; expected " + gain_key + " / " + mass_key +
                        " <= " + FormatNumber(limit) + " (a lower gain or a larger mass)");
}

class HandDevice final : public Device {
 public:
  HandDevice(std::vector<Keyframe> target, const HandSettings& hand, Specifications specs)
      : target_(std::move(target)), hand_(hand), specs_(std::move(specs)) {
    X_DT_ = target_.Sample(target_.keyframes().front().t).X_DT;
  }

  const Specifications& specifications() const override { return specs_; }

  // Re-opening starts a new session: the next Read() places the hand on its target again.
  void Open() override {
    initialized_ = false;
    display_ = Wrench{};
  }

  DeviceState Read(double t) noexcept override {
    if (std::isfinite(t)) {
      if (!initialized_) {
        X_DT_ = target_.Sample(t).X_DT;
        V_DT_ = Twist{};
        last_t_ = t;
        initialized_ = true;
      } else {
        Advance(t);
      }
    }
    DeviceState state;
    state.t = t;
    state.X_DT = X_DT_;
    state.V_DT = V_DT_;
    return state;
  }

  // A non-finite command would poison the hand state; a real amplifier would output zero.
  void SetWrench(const Wrench& w_D) noexcept override { display_ = IsFinite(w_D) ? w_D : Wrench{}; }

 private:
  void Advance(double t) noexcept;
  void Step(double h, const internal::TrackSample& target) noexcept;

  internal::PoseTrack target_;
  HandSettings hand_;
  Specifications specs_;
  Pose X_DT_;
  Twist V_DT_;
  Wrench display_;  // the wrench the device pushes the hand with, held between commands
  double last_t_ = 0.0;
  bool initialized_ = false;
};

void HandDevice::Advance(double t) noexcept {
  double span = t - last_t_;
  if (!(span > 0.0)) return;  // time stood still or ran backwards: nothing to integrate
  double steps = std::max(1.0, std::ceil(span / kMaxStep - kStepCountSlack));
  if (steps > kMaxSteps) {
    steps = kMaxSteps;
    span = kMaxSteps * kMaxStep;
  }
  const double h = span / steps;
  const double t0 = t - span;
  const int n = static_cast<int>(steps);
  for (int i = 0; i < n; ++i) Step(h, target_.Sample(t0 + static_cast<double>(i) * h));
  last_t_ = t;
}

// Semi-implicit (symplectic) Euler: forces from the state at the start of the step update the
// velocity, and the new velocity moves the pose. Unlike explicit Euler it does not pump energy
// into an undamped spring, which matters for the wall-contact loop.
void HandDevice::Step(double h, const internal::TrackSample& target) noexcept {
  const Vec3 force = hand_.stiffness * (target.X_DT.p - X_DT_.p) +
                     hand_.damping * (target.V_DT.v - V_DT_.v) + display_.f;
  V_DT_.v += (h / hand_.mass) * force;
  X_DT_.p += h * V_DT_.v;

  // Orientation error as the rotation vector of q_target q^-1, expressed in D like w.
  const Vec3 error = RotationVectorFromQuat(target.X_DT.q * X_DT_.q.conjugate());
  const Vec3 torque =
      hand_.rot_stiffness * error + hand_.rot_damping * (target.V_DT.w - V_DT_.w) + display_.tau;
  V_DT_.w += (h / hand_.inertia) * torque;
  X_DT_.q = QuatFromRotationVector(h * V_DT_.w) * X_DT_.q;
  X_DT_.q.normalize();
}

}  // namespace

void HandSettings::Validate() const {
  RequireInRange(mass, 1e-3, 1e3, "device.hand.mass", "kg");
  RequirePositive(stiffness, "device.hand.stiffness", "N/m", 1e6);
  RequirePositive(damping, "device.hand.damping", "N*s/m", 1e5);
  RequireInRange(inertia, 1e-7, 1e2, "device.hand.inertia", "kg*m^2");
  RequirePositive(rot_stiffness, "device.hand.rot_stiffness", "N*m/rad", 1e4);
  RequirePositive(rot_damping, "device.hand.rot_damping", "N*m*s/rad", 1e3);
  RequireRate(stiffness, mass, kMaxStiffnessPerMass, "device.hand.stiffness", "device.hand.mass");
  RequireRate(damping, mass, kMaxDampingPerMass, "device.hand.damping", "device.hand.mass");
  RequireRate(rot_stiffness, inertia, kMaxStiffnessPerMass, "device.hand.rot_stiffness",
              "device.hand.inertia");
  RequireRate(rot_damping, inertia, kMaxDampingPerMass, "device.hand.rot_damping",
              "device.hand.inertia");
}

std::unique_ptr<Device> MakeHandDevice(std::vector<Keyframe> target, const HandSettings& hand,
                                       const Specifications& specs) {
  hand.Validate();
  internal::ValidateKeyframes(target, "hand device: target keyframe");
  return std::make_unique<HandDevice>(std::move(target), hand, specs);
}

}  // namespace mrh::device
