// SPDX-License-Identifier: Apache-2.0
// FieldsFor: the rendering keys a method reads, as its descriptor states them.
#include "viewer/method_fields.h"

#include <optional>

#include "mrh/engine/method.h"

namespace mrh::viewer::internal {

MethodFields FieldsFor(const std::string& method) {
  const std::optional<engine::MethodDescriptor> d = engine::FindMethod(method);
  if (!d) return {.stiffness = true};
  const engine::MethodSettingsUsed& s = d->settings;
  return {.stiffness = s.stiffness,
          .friction = s.friction,
          .rot_stiffness = s.rot_stiffness,
          .coupling = s.coupling,
          .torque = s.torque};
}

}  // namespace mrh::viewer::internal
