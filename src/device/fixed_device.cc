// SPDX-License-Identifier: Apache-2.0
// The fixed device: one pose held forever, the displayed wrench ignored.
#include <utility>

#include "mrh/core/error.h"
#include "mrh/device/simulated.h"

namespace mrh::device {
namespace {

class FixedDevice final : public Device {
 public:
  FixedDevice(Pose X_DT, Specifications specs) : X_DT_(std::move(X_DT)), specs_(std::move(specs)) {}

  const Specifications& specifications() const override { return specs_; }

  DeviceState Read(double t) noexcept override {
    DeviceState state;
    state.t = t;
    state.X_DT = X_DT_;
    return state;
  }

  // An immovable pointer: whatever is displayed cannot move it.
  void SetWrench(const Wrench& /*w_D*/) noexcept override {}

 private:
  Pose X_DT_;
  Specifications specs_;
};

}  // namespace

std::unique_ptr<Device> MakeFixedDevice(const Pose& X_DT, const Specifications& specs) {
  if (!IsFinite(X_DT) || X_DT.q.norm() == 0.0) {
    throw InvalidArgument(
        "fixed device: pose is not finite or its quaternion has zero norm; expected a finite "
        "position and a rotation, e.g. qw = 1 for identity");
  }
  Pose X = X_DT;
  X.q.normalize();
  return std::make_unique<FixedDevice>(X, specs);
}

}  // namespace mrh::device
