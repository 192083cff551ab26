// SPDX-License-Identifier: Apache-2.0
// The table of known device models, with figures from the vendors' published data sheets (see
// the caveat below); where a sheet gives per-axis values the smallest is taken.
#include "mrh/device/models.h"

#include <array>

namespace mrh::device {
namespace {

// Sources (vendor product data sheets / specification pages, as published). These figures were
// taken from those sheets as remembered by the author and could not be re-checked against a
// sheet while writing this table (no data sheet was reachable here): check them against your
// device's sheet, and override any of them with device.limits.
// - 3D Systems "Touch" and "Touch X" haptic device specification sheets (formerly Geomagic
//   Touch / Phantom Omni and Geomagic Touch X / Phantom Desktop): workspace 160 x 120 x 70 mm
//   (Touch) and 160 x 120 x 120 mm (Touch X), peak force 3.3 N / 7.9 N, stiffness
//   x 1.26, y 2.31, z 1.02 N/mm (Touch) and x 1.86, y 2.35, z 1.48 N/mm (Touch X).
// - 3D Systems "Phantom Premium" specification sheet, model 1.5 (standard, 3-DOF output):
//   workspace 381 x 267 x 191 mm, peak force 8.5 N, stiffness 3.5 N/mm.
// - Novint "Falcon" technical specifications: 4 x 4 x 4 in (≈ 10 cm) workspace, force
//   capability > 2 lb (8.9 N). The sheet lists no stiffness; 3000 N/m is what CHAI3D's Falcon
//   driver declares (cFalconDevice).
// - Force Dimension "omega.x" data sheet (omega.3 / .6 / .7): translation workspace
//   Ø 160 x 110 mm, continuous force 12.0 N, closed-loop stiffness 14.5 N/mm; orientation of
//   omega.6/.7 is sensed, not actuated (3-DOF output; omega.7's 8 N gripper is not modelled).
// - Force Dimension "sigma.7" data sheet: Ø 190 x 130 mm, force 20.0 N, torque 0.4 N·m,
//   stiffness 14.5 N/mm (6-DOF output).
// - Force Dimension "lambda.7" data sheet: Ø 240 x 180 mm, force 20.0 N, torque 0.3 N·m,
//   stiffness 10 N/mm (6-DOF output).
// - Haply "Inverse3" specifications: workspace Ø 400 mm hemisphere-like reach, continuous force
//   3.3 N (peak 10 N), stiffness ≈ 3 N/mm; 3-DOF output (the VerseGrip handle only senses).
constexpr std::array<DeviceModel, 10> kModels{{
    {"touch", "3D Systems Touch", 3.3, 0.0, 1020.0, 0.08, 3},
    {"touch_x", "3D Systems Touch X", 7.9, 0.0, 1480.0, 0.08, 3},
    {"phantom_premium_1.5", "3D Systems Phantom Premium 1.5", 8.5, 0.0, 3500.0, 0.19, 3},
    {"falcon", "Novint Falcon", 8.9, 0.0, 3000.0, 0.05, 3},
    {"omega.3", "Force Dimension omega.3", 12.0, 0.0, 14500.0, 0.08, 3},
    {"omega.6", "Force Dimension omega.6", 12.0, 0.0, 14500.0, 0.08, 3},
    {"omega.7", "Force Dimension omega.7", 12.0, 0.0, 14500.0, 0.08, 3},
    {"sigma.7", "Force Dimension sigma.7", 20.0, 0.4, 14500.0, 0.095, 6},
    {"lambda.7", "Force Dimension lambda.7", 20.0, 0.3, 10000.0, 0.12, 6},
    {"inverse3", "Haply Inverse3", 10.0, 0.0, 3000.0, 0.2, 3},
}};

}  // namespace

std::span<const DeviceModel> DeviceModels() {
  return kModels;
}

const DeviceModel* FindDeviceModel(std::string_view name) {
  for (const DeviceModel& model : kModels) {
    if (model.name == name) return &model;
  }
  return nullptr;
}

Specifications ModelSpecifications(const DeviceModel& model) {
  Specifications specs;
  specs.model = std::string(model.name);
  specs.max_force = model.max_force;
  specs.max_torque = model.max_torque;
  specs.max_stiffness = model.max_stiffness;
  specs.workspace_min = Vec3::Constant(-model.workspace_radius);
  specs.workspace_max = Vec3::Constant(model.workspace_radius);
  specs.has_torque = model.output_dof == 6;
  return specs;
}

std::string DeviceModelNames() {
  std::string names;
  for (const DeviceModel& model : kModels) {
    if (!names.empty()) names += ", ";
    names += "\"" + std::string(model.name) + "\"";
  }
  return names;
}

}  // namespace mrh::device
