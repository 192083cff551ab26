// SPDX-License-Identifier: Apache-2.0
// The fixed device: one pose held forever, the displayed wrench ignored.
#include <utility>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"
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
  const Problem problem = PoseProblem(X_DT.p, X_DT.q);
  if (problem) throw InvalidArgument("fixed device: pose: " + problem.Text());
  Pose X = X_DT;
  X.q.normalize();
  return std::make_unique<FixedDevice>(X, specs);
}

}  // namespace mrh::device
