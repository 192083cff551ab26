// SPDX-License-Identifier: Apache-2.0
// Factories of the built-in methods' haptic halves.
#include "mrh/haptic/methods.h"

#include "contact_volume_haptic.h"
#include "local_contact_haptic.h"
#include "local_dynamics_6dof_haptic.h"
#include "local_dynamics_haptic.h"
#include "penalty_sum_haptic.h"
#include "point_penalty_haptic.h"
#include "proxy_haptic.h"
#include "virtual_coupling_haptic.h"

namespace mrh::haptic {

std::unique_ptr<MethodHaptic> MakePointPenaltyHaptic(double radius, double stiffness,
                                                     double damping, double friction) {
  return std::make_unique<internal::PointPenaltyHaptic>(radius, stiffness, damping, friction);
}

std::unique_ptr<MethodHaptic> MakeProxyHaptic(const render::ProxyRendererSettings& settings) {
  return std::make_unique<internal::ProxyHaptic>(settings);
}

std::unique_ptr<MethodHaptic> MakePenaltySumHaptic(const render::PenaltySumSettings& settings) {
  return std::make_unique<internal::PenaltySumHaptic>(settings);
}

std::unique_ptr<MethodHaptic> MakeContactVolumeHaptic() {
  return std::make_unique<internal::ContactVolumeHaptic>();
}

std::unique_ptr<MethodHaptic> MakeVirtualCouplingHaptic(const render::CouplingGains& gains) {
  return std::make_unique<internal::VirtualCouplingHaptic>(gains);
}

std::unique_ptr<MethodHaptic> MakeLocalDynamicsHaptic(double radius, double stiffness,
                                                      double damping) {
  return std::make_unique<internal::LocalDynamicsHaptic>(radius, stiffness, damping);
}

std::unique_ptr<MethodHaptic> MakeLocalContactHaptic(double radius, double stiffness,
                                                     double damping, double friction) {
  auto half = std::make_unique<internal::LocalContactHaptic>(radius, stiffness, damping);
  half->SetFriction(friction);
  return half;
}

std::vector<std::unique_ptr<MethodHaptic>> MakeLocalContactHapticGroup(
    const std::vector<PointerGains>& pointers) {
  std::vector<std::unique_ptr<MethodHaptic>> group;
  internal::LocalContactHaptic* owner = nullptr;
  for (std::size_t i = 0; i < pointers.size(); ++i) {
    auto half = std::make_unique<internal::LocalContactHaptic>(
        pointers[i].radius, pointers[i].stiffness, pointers[i].damping);
    half->SetFriction(pointers[i].friction);
    half->ShareIsland(owner, i + 1 == pointers.size());
    if (owner == nullptr) owner = half.get();
    group.push_back(std::move(half));
  }
  return group;
}

std::unique_ptr<MethodHaptic> MakeLocalDynamics6dofHaptic(
    const render::ProxyRendererSettings& settings) {
  return std::make_unique<internal::LocalDynamics6dofHaptic>(settings);
}

std::vector<std::unique_ptr<MethodHaptic>> MakeLocalDynamics6dofHapticGroup(
    const std::vector<render::ProxyRendererSettings>& pointers) {
  std::vector<std::unique_ptr<MethodHaptic>> group;
  internal::LocalDynamics6dofHaptic* owner = nullptr;
  for (std::size_t i = 0; i < pointers.size(); ++i) {
    auto half = std::make_unique<internal::LocalDynamics6dofHaptic>(pointers[i]);
    half->ShareIsland(owner, i + 1 == pointers.size());
    if (owner == nullptr) owner = half.get();
    group.push_back(std::move(half));
  }
  return group;
}

const render::ProxyOutput* LocalDynamics6dofLastOutput(const MethodHaptic& method) noexcept {
  const auto* m = dynamic_cast<const internal::LocalDynamics6dofHaptic*>(&method);
  return m == nullptr ? nullptr : &m->last_output();
}

const render::TickIr* LocalDynamics6dofLastTickIr(const MethodHaptic& method) noexcept {
  const auto* m = dynamic_cast<const internal::LocalDynamics6dofHaptic*>(&method);
  return m == nullptr ? nullptr : &m->last_tick_ir();
}

const render::LocalContactSolver* LocalDynamics6dofSolver(const MethodHaptic& method) noexcept {
  const auto* m = dynamic_cast<const internal::LocalDynamics6dofHaptic*>(&method);
  return m == nullptr ? nullptr : &m->solver();
}

const render::ProxyOutput* ProxyLastOutput(const MethodHaptic& method) noexcept {
  const auto* proxy = dynamic_cast<const internal::ProxyHaptic*>(&method);
  return proxy == nullptr ? nullptr : &proxy->last_output();
}

const render::TickIr* ProxyLastTickIr(const MethodHaptic& method) noexcept {
  const auto* proxy = dynamic_cast<const internal::ProxyHaptic*>(&method);
  return proxy == nullptr ? nullptr : &proxy->last_tick_ir();
}

}  // namespace mrh::haptic
