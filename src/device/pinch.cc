// SPDX-License-Identifier: Apache-2.0
// PinchKeyframes: two fingertips' targets for a pinch, lift, hold and release.
#include "mrh/device/pinch.h"

#include <cmath>
#include <string>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::device {
namespace {

void RequirePositive(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InvalidArgument(std::string("pinch.") + name + " = " + FormatNumber(value) +
                          "; expected a finite value > 0");
  }
}

}  // namespace

void PinchSettings::Validate() const {
  RequirePositive(open_width, "open_width");
  RequirePositive(grip_width, "grip_width");
  RequirePositive(close_time, "close_time");
  RequirePositive(lift_time, "lift_time");
  RequirePositive(hold_time, "hold_time");
  RequirePositive(lower_time, "lower_time");
  RequirePositive(open_time, "open_time");
  if (grip_width >= open_width) {
    throw InvalidArgument("pinch.grip_width = " + FormatNumber(grip_width) +
                          " m is not below pinch.open_width = " + FormatNumber(open_width) +
                          " m; the fingers must close");
  }
  if (!(std::isfinite(lift) && lift >= 0.0)) {
    throw InvalidArgument("pinch.lift = " + FormatNumber(lift) +
                          " m; expected a finite value >= 0");
  }
  if (!(center.allFinite() && axis.allFinite() && axis.norm() > 0.0)) {
    throw InvalidArgument("pinch.center / pinch.axis: expected finite vectors, a non-zero axis");
  }
}

std::vector<Keyframe> PinchKeyframes(const PinchSettings& pinch, int finger) {
  pinch.Validate();
  if (finger != 0 && finger != 1) {
    throw InvalidArgument("pinch finger = " + std::to_string(finger) + "; expected 0 or 1");
  }
  const double side = finger == 0 ? -0.5 : 0.5;
  const Vec3 axis = pinch.axis.normalized();
  const Vec3 up = Vec3::UnitZ() * pinch.lift;
  const Vec3 open = pinch.center + side * pinch.open_width * axis;
  const Vec3 grip = pinch.center + side * pinch.grip_width * axis;
  const auto at = [](double t, const Vec3& p) {
    return Keyframe{t, Pose{p, Quat::Identity()}};
  };
  double t = 0.0;
  std::vector<Keyframe> frames{at(t, open)};
  frames.push_back(at(t += pinch.close_time, grip));
  frames.push_back(at(t += pinch.lift_time, grip + up));
  frames.push_back(at(t += pinch.hold_time, grip + up));
  frames.push_back(at(t += pinch.lower_time, grip));
  frames.push_back(at(t += pinch.open_time, open));
  return frames;
}

}  // namespace mrh::device
