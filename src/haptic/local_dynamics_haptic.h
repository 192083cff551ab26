// SPDX-License-Identifier: Apache-2.0
// Haptic half of the Chapter-4 method: local simulation of the neighbors at the haptic rate.
#pragma once

#include <array>
#include <cstdint>

#include "mrh/haptic/method_haptic.h"
#include "mrh/haptic/methods.h"
#include "mrh/render/contact_transients.h"
#include "mrh/render/local_body.h"
#include "normal_carry.h"

namespace mrh::haptic::internal {

using haptic::kLocalBodyFault;

/// Counters of the haptic half (haptic thread; read them after the run).
struct LocalDynamicsHapticCounters {
  std::int64_t ticks = 0;
  std::int64_t local_faults = 0;  ///< local bodies stopped on a non-finite state
  std::int64_t corrections = 0;   ///< eq. 4.18 velocity corrections applied
};

/// The haptic half of `local-dynamics` (thesis ch. 4): simulates each dynamic neighbor of the
/// snapshot locally from its accelerance A and bias b (eq. 4.13–4.15) and renders corrected
/// eq. 4.11 against planes that move with it, feeding the reaction (eq. 4.12) to the local
/// simulation in the same tick; a static or kinematic body is blended between its step poses as
/// in B4. EndPeriod reports the local end states for the physics half's overwrite
/// (eq. 4.16–4.17). Its physics half is physics::internal::LocalDynamicsPhysics.
class LocalDynamicsHaptic final : public MethodHaptic {
 public:
  /// radius (m), stiffness k (N/m), damping d (N·s/m) of eq. 4.11.
  LocalDynamicsHaptic(double radius, double stiffness, double damping)
      : radius_(radius), stiffness_(stiffness), damping_(damping) {}

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  const LocalDynamicsHapticCounters& haptic_counters() const { return haptic_counters_; }

  /// The local simulation of world body `body`, or null when it is not simulated locally.
  /// Haptic thread only (tests read it between ticks). RT-safe.
  const render::LocalBody* local_body(int body) const noexcept;

 private:
  void RenderContacts(const TickInput& in, double alpha, TickOutput* out) noexcept;
  void StepLocalBodies(const TickInput& in, TickOutput* out) noexcept;

  double radius_;
  double stiffness_;
  double damping_;
  ir::PhysicsSnapshot snapshot_;
  // Two generations of local bodies, indexed like the bodies of the snapshot that made them:
  // Adopt() builds the new one from the old one.
  using LocalBodies = std::array<render::LocalBody, ir::kMaxNeighborBodies>;

  LocalBodies& local() noexcept { return locals_[current_]; }

  const LocalBodies& local() const noexcept { return locals_[current_]; }

  std::array<LocalBodies, 2> locals_{};
  std::size_t current_ = 0;
  std::array<bool, ir::kMaxNeighborBodies> pending_{};
  std::array<Twist, ir::kMaxNeighborBodies> pending_dV_{};
  ContactNormals previous_n_{};
  ContactNormals rendered_n_{};
  std::array<Vec3, ir::kMaxNeighborBodies> tick_force_{};
  std::array<Vec3, ir::kMaxNeighborBodies> tick_torque_{};
  ir::HapticReport period_;
  // Material vibration at contact onset, added to the rendered force.
  render::ContactTransients transients_;
  LocalDynamicsHapticCounters haptic_counters_;
};

}  // namespace mrh::haptic::internal
