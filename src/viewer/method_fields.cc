// SPDX-License-Identifier: Apache-2.0
// FieldsFor: the rendering keys each built-in method reads (method_registry.cc, physics/*).
#include "viewer/method_fields.h"

namespace mrh::viewer::internal {

MethodFields FieldsFor(const std::string& method) {
  // 6-DOF proxy (Ch. 3) and its local-dynamics variant: k_t, d_t, k_r and μ of the proxy.
  if (method == "proxy-6dof" || method == "local-dynamics-6dof") {
    return {.stiffness = true, .friction = true, .rot_stiffness = true, .torque = true};
  }
  // B5: per-contact springs k, d; torque from the contacts' lever arms.
  if (method == "penalty-sum") return {.stiffness = true, .torque = true};
  // B2: the volume penalty's k, d and μ; the pointer's wrench includes a torque.
  if (method == "contact-volume") return {.stiffness = true, .friction = true, .torque = true};
  // B3: only the coupling spring-damper; MuJoCo's own contacts push the tool.
  if (method == "virtual-coupling") return {.coupling = true, .torque = true};
  // single-rate, impulse, local-dynamics: the 3-DOF point penalty k, d of eq. 4.11.
  return {.stiffness = true};
}

}  // namespace mrh::viewer::internal
