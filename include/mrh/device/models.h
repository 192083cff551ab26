// SPDX-License-Identifier: Apache-2.0
// Known haptic device models and their specifications (defaults for `device.limits`).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "mrh/device/device.h"

namespace mrh::device {

/// One commercial device as its vendor's data sheet gives it. Session: `device.model`.
struct DeviceModel {
  std::string_view name;         ///< session name, e.g. "touch", "omega.6"
  std::string_view description;  ///< vendor and product
  double max_force;              ///< N, peak force the data sheet lists
  double max_torque;             ///< N·m (0 for 3-DOF force output)
  double max_stiffness;          ///< N/m, the data sheet's (smallest-axis) closed-loop stiffness
  double workspace_radius;       ///< m, half the largest translational workspace extent
  int output_dof;                ///< 3 (force only) or 6 (force and torque)
};

/// Every known model, in a stable order. RT-safe (static data).
std::span<const DeviceModel> DeviceModels();

/// The model named `name`, or nullptr. RT-safe.
const DeviceModel* FindDeviceModel(std::string_view name);

/// The model's specifications: limits as listed, workspace a cube of half-side
/// workspace_radius about the device origin, has_torque = (output_dof == 6). Not RT-safe.
Specifications ModelSpecifications(const DeviceModel& model);

/// "\"touch\", \"touch_x\", ..." for messages. Not RT-safe.
std::string DeviceModelNames();

}  // namespace mrh::device
