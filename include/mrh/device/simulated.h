// SPDX-License-Identifier: Apache-2.0
// Simulated devices: fixed, scripted, hand (closed-loop simulated user) and replay.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "mrh/device/device.h"

namespace mrh::device {

/// A timed tool pose (device frame) for scripted trajectories.
struct Keyframe {
  double t = 0.0;  ///< s
  Pose X_DT;
};

/// Holds one pose forever; the displayed wrench is ignored (the thesis' immovable pointer).
std::unique_ptr<Device> MakeFixedDevice(const Pose& X_DT, const Specifications& specs = {});

/// Piecewise-linear poses (lerp + slerp) through keyframes sorted by time; holds the first pose
/// before the first keyframe and the last after the last one. Velocity is the segment's slope.
/// @throws mrh::InvalidArgument if empty, times not strictly increasing, or values not finite.
std::unique_ptr<Device> MakeScriptedDevice(std::vector<Keyframe> keyframes,
                                           const Specifications& specs = {});

/// Reads keyframes from a CSV file with header `t,x,y,z,qw,qx,qy,qz` (extra columns ignored).
/// @throws mrh::InvalidArgument naming file and line on a malformed row.
std::vector<Keyframe> LoadKeyframesCsv(const std::filesystem::path& path);

/// Parameters of the simulated hand.
struct HandSettings {
  double mass = 0.5;           ///< kg, effective mass of hand + grip
  double stiffness = 300.0;    ///< N/m, pull toward the scripted target
  double damping = 20.0;       ///< N·s/m
  double inertia = 5e-4;       ///< kg·m² (isotropic)
  double rot_stiffness = 2.0;  ///< N·m/rad
  double rot_damping = 0.05;   ///< N·m·s/rad
  /// @throws mrh::InvalidArgument naming the key if a value is not finite and > 0.
  void Validate() const;
};

/// A closed-loop simulated user: a mass–spring–damper hand pulled toward a scripted target pose
/// and pushed by the displayed wrench, integrated with semi-implicit Euler at the tick rate.
std::unique_ptr<Device> MakeHandDevice(std::vector<Keyframe> target, const HandSettings& hand,
                                       const Specifications& specs = {});

/// Replays the tool poses of a recorded run (`ticks.csv` of `mrh run`, columns t,px,py,pz,qw,qx,
/// qy,qz), interpolated by time. @throws mrh::InvalidArgument naming file and line.
std::unique_ptr<Device> MakeReplayDevice(const std::filesystem::path& ticks_csv,
                                         const Specifications& specs = {});

}  // namespace mrh::device
