// SPDX-License-Identifier: Apache-2.0
// Keyframe validation and the piecewise-linear pose trajectory.
#include <algorithm>
#include <cmath>
#include <utility>

#include "device/track_impl.h"
#include "mrh/core/assert.h"
#include "mrh/core/error.h"
#include "mrh/core/spatial.h"
#include "mrh/core/validate.h"

namespace mrh::device::internal {

void ValidateKeyframes(std::vector<Keyframe>& keyframes, const std::string& what) {
  if (keyframes.empty()) {
    throw InvalidArgument(what + "s: none given; expected at least one keyframe {t, pose}");
  }
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    Keyframe& k = keyframes[i];
    const std::string where = what + " " + std::to_string(i);
    Problem problem = KeyframeTimeProblem(k.t, i > 0 ? keyframes[i - 1].t : NAN);
    if (!problem) problem = PoseProblem(k.X_DT.p, k.X_DT.q);
    if (problem) throw InvalidArgument(where + ": " + problem.Text());
    k.X_DT.q.normalize();
  }
}

PoseTrack::PoseTrack(std::vector<Keyframe> keyframes) : keyframes_(std::move(keyframes)) {
  MRH_DEMAND(!keyframes_.empty());
  slopes_.reserve(keyframes_.size() - 1);
  for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
    const Keyframe& a = keyframes_[i];
    const Keyframe& b = keyframes_[i + 1];
    const double dt = b.t - a.t;
    // slerp(alpha) = exp(alpha r) q_a with r the short-arc rotation vector of q_b q_a^-1, so the
    // angular velocity (in D, the frame q maps into) is constant: w = r / dt.
    const Vec3 r = RotationVectorFromQuat(b.X_DT.q * a.X_DT.q.conjugate());
    slopes_.push_back(Twist{(b.X_DT.p - a.X_DT.p) / dt, r / dt});
  }
}

TrackSample PoseTrack::Sample(double t) const noexcept {
  const Keyframe& first = keyframes_.front();
  const Keyframe& last = keyframes_.back();
  if (!(t >= first.t)) return TrackSample{first.X_DT, Twist{}};
  if (t >= last.t) return TrackSample{last.X_DT, Twist{}};
  // First keyframe after t; it exists and is not the first because first.t <= t < last.t.
  const auto after =
      std::upper_bound(keyframes_.begin(), keyframes_.end(), t, [](double time, const Keyframe& k) {
        return time < k.t;
      });
  const auto i = static_cast<std::size_t>(after - keyframes_.begin()) - 1;
  const Keyframe& a = keyframes_[i];
  const Keyframe& b = keyframes_[i + 1];
  const double alpha = (t - a.t) / (b.t - a.t);
  Pose X = Interpolate(a.X_DT, b.X_DT, alpha);
  X.q.normalize();
  return TrackSample{X, slopes_[i]};
}

namespace {

class TrackDevice final : public Device {
 public:
  TrackDevice(std::vector<Keyframe> keyframes, Specifications specs)
      : track_(std::move(keyframes)), specs_(std::move(specs)) {}

  const Specifications& specifications() const override { return specs_; }

  DeviceState Read(double t) noexcept override {
    const TrackSample sample = track_.Sample(t);
    DeviceState state;
    state.t = t;
    state.X_DT = sample.X_DT;
    state.V_DT = sample.V_DT;
    return state;
  }

  // Open-loop playback: the displayed wrench cannot change a script or a recording.
  void SetWrench(const Wrench& /*w_D*/) noexcept override {}

 private:
  PoseTrack track_;
  Specifications specs_;
};

}  // namespace

std::unique_ptr<Device> MakeTrackDevice(std::vector<Keyframe> keyframes,
                                        const Specifications& specs) {
  return std::make_unique<TrackDevice>(std::move(keyframes), specs);
}

}  // namespace mrh::device::internal
