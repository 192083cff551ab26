// SPDX-License-Identifier: Apache-2.0
// A piecewise-linear pose trajectory (lerp + slerp) sampled by time, shared by the scripted,
// hand and replay devices.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/device/simulated.h"

namespace mrh::device::internal {

/// A pose and its velocity on a trajectory at one time (device frame D).
struct TrackSample {
  Pose X_DT;
  Twist V_DT;
};

/// Checks keyframes and normalizes their quaternions in place. `what` names one keyframe in a
/// message, e.g. "scripted device: keyframe" gives "scripted device: keyframe 3: ...".
/// @throws mrh::InvalidArgument if empty, a value is not finite, a quaternion has zero norm, or
/// times are not strictly increasing. Not RT-safe.
void ValidateKeyframes(std::vector<Keyframe>& keyframes, const std::string& what);

/// Piecewise-linear interpolation through validated keyframes. Before the first keyframe it holds
/// the first pose and after the last it holds the last, with zero velocity in both cases. Inside
/// segment i, [t_i, t_i+1), the velocity is the segment's slope: v = dp / dt and w = the rotation
/// vector of q_i+1 q_i^-1 (short arc) / dt, both in D. Read-only after construction.
class PoseTrack {
 public:
  /// @pre keyframes passed ValidateKeyframes. Not RT-safe.
  explicit PoseTrack(std::vector<Keyframe> keyframes);

  /// The pose and velocity at time t (s); a NaN t holds the first pose. RT-safe (binary search,
  /// no allocation).
  TrackSample Sample(double t) const noexcept;

  const std::vector<Keyframe>& keyframes() const noexcept { return keyframes_; }

 private:
  std::vector<Keyframe> keyframes_;
  std::vector<Twist> slopes_;  // one per segment, precomputed so Sample() stays cheap
};

/// A device that plays validated keyframes open-loop: Read(t) samples the track (DeviceState::t =
/// t), SetWrench() is ignored. Backs the scripted and replay devices. Not RT-safe (setup).
std::unique_ptr<Device> MakeTrackDevice(std::vector<Keyframe> keyframes,
                                        const Specifications& specs);

}  // namespace mrh::device::internal
