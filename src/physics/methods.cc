// SPDX-License-Identifier: Apache-2.0
// Factories of the built-in methods' physics halves.
#include "mrh/physics/methods.h"

#include <fmt/format.h>

#include "contact_volume_physics.h"
#include "local_contact_physics.h"
#include "local_dynamics_6dof_physics.h"
#include "local_dynamics_physics.h"
#include "mrh/core/error.h"
#include "mrh/physics/local_dynamics.h"
#include "mrh/world/world.h"
#include "point_penalty_physics.h"
#include "proxy_physics.h"
#include "virtual_coupling_physics.h"

namespace mrh::physics {

double PointerRadiusFor3Dof(const MethodContext& context) {
  if (context.pointer_radius > 0.0) return context.pointer_radius;
  const std::string& body = context.settings->pointer.body;
  throw SceneError(fmt::format(
      "{}: pointer.body = '{}' has no sphere geom and pointer.radius is not set, which method "
      "'{}' (3-DOF) needs; set pointer.radius (m) in the session or add a sphere geom to the body",
      context.world->origin(), body, context.settings->method));
}

std::unique_ptr<MethodPhysics> MakePointPenaltyPhysics(const MethodContext& context) {
  return std::make_unique<internal::PointPenaltyPhysics>(context);
}

std::unique_ptr<MethodPhysics> MakeProxyPhysics(const MethodContext& context) {
  return std::make_unique<internal::ProxyPhysics>(context);
}

std::unique_ptr<MethodPhysics> MakeLocalDynamicsPhysics(const MethodContext& context) {
  return std::make_unique<internal::LocalDynamicsPhysics>(context);
}

std::unique_ptr<MethodPhysics> MakeLocalDynamicsPhysics(const MethodContext& context,
                                                        const LocalDynamicsOptions& options) {
  return std::make_unique<internal::LocalDynamicsPhysics>(context, options);
}

const LocalDynamicsCounters* LocalDynamicsCountersOf(const MethodPhysics& method) noexcept {
  const auto* ld = dynamic_cast<const internal::LocalDynamicsPhysics*>(&method);
  return ld == nullptr ? nullptr : &ld->counters();
}

const world::PerturberCounters* PerturberCountersOf(const MethodPhysics& method) noexcept {
  const auto* ld = dynamic_cast<const internal::LocalDynamicsPhysics*>(&method);
  return ld == nullptr ? nullptr : &ld->perturber_counters();
}

std::unique_ptr<MethodPhysics> MakeContactVolumePhysics(const MethodContext& context) {
  return std::make_unique<internal::ContactVolumePhysics>(context);
}

std::unique_ptr<MethodPhysics> MakeVirtualCouplingPhysics(const MethodContext& context) {
  return std::make_unique<internal::VirtualCouplingPhysics>(context);
}

render::CouplingGains ResolveCouplingGains(const MethodContext& context) {
  return internal::ResolveCouplingGains(context.world->body(context.pointer_body),
                                        context.settings->rendering);
}

std::unique_ptr<MethodPhysics> MakeLocalContactPhysics(const MethodContext& context) {
  return std::make_unique<internal::LocalContactPhysics>(context);
}

std::unique_ptr<MethodPhysics> MakeLocalDynamics6dofPhysics(const MethodContext& context) {
  return std::make_unique<internal::LocalDynamics6dofPhysics>(context);
}

}  // namespace mrh::physics
