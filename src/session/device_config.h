// SPDX-License-Identifier: Apache-2.0
// Parsing of the session's `device` block into a DeviceConfig.
#pragma once

#include "mrh/core/spatial.h"
#include "mrh/session/session.h"
#include "session/json_node.h"

namespace mrh::session::internal {

/// Reads and checks the `device` block: the type, the keys that type accepts and requires
/// (pose / keyframes xor trajectory / replay), hand parameters, limits (> 0) and calibration.
/// Quaternions are normalized; relative paths resolve against the session's folder and must
/// exist. @throws mrh::InvalidArgument naming the dotted key.
DeviceConfig ParseDevice(const Node& device);

/// The stiffness limit: when the session states it (device.model or
/// device.limits.max_stiffness), `stiffness` (rendering.stiffness, N/m) must not exceed it.
/// @throws mrh::InvalidArgument naming both keys and values.
void CheckStiffnessLimit(const Node& root, const DeviceConfig& device, double stiffness);

/// A unit quaternion from (qw, qx, qy, qz) read at `node` (for messages).
/// @throws mrh::InvalidArgument if the norm is (nearly) zero.
Quat ParseQuaternion(const Node& node, double qw, double qx, double qy, double qz);

}  // namespace mrh::session::internal
