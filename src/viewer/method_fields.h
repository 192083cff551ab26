// SPDX-License-Identifier: Apache-2.0
// Which gains and readouts the viewer's panel shows for a rendering method.
#pragma once

#include <string>

namespace mrh::viewer::internal {

/// The session keys a method reads among the panel's gain fields, and whether it renders a
/// torque. The panel shows only these, so an edit always changes what the user feels.
struct MethodFields {
  bool stiffness = false;      ///< rendering.stiffness and rendering.damping
  bool friction = false;       ///< rendering.friction
  bool rot_stiffness = false;  ///< rendering.rot_stiffness
  bool coupling = false;       ///< rendering.coupling_stiffness and coupling_damping
  bool torque = false;         ///< the method renders a torque (6-DOF)
};

/// The fields of a registered method (engine::MethodDescriptor::settings); an unknown name shows
/// stiffness and damping, which every penalty-like method reads.
MethodFields FieldsFor(const std::string& method);

}  // namespace mrh::viewer::internal
