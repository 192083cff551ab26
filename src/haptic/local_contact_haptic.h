// SPDX-License-Identifier: Apache-2.0
// local-dynamics with the contact local model: the haptic half.
#pragma once

#include <array>
#include <cstdint>

#include "mrh/haptic/method_haptic.h"
#include "mrh/haptic/methods.h"
#include "mrh/render/contact_transients.h"
#include "mrh/render/local_contact_solver.h"
#include "mrh/render/point_friction.h"
#include "normal_carry.h"

namespace mrh::haptic::internal {

// TickOutput::status: kLocalBodyFault when an island body became non-finite and was stopped.
using haptic::kLocalBodyFault;

/// Counters of the contact model's haptic half (haptic thread; read them after the run).
struct LocalContactHapticCounters {
  std::int64_t ticks = 0;         ///< haptic ticks
  std::int64_t local_faults = 0;  ///< non-finite local states
};

/// The haptic half of `local-dynamics`, local model "contact": the island of the snapshot's
/// ir::LocalContactModel is simulated at 1 kHz under gravity, the pointer's reaction and its own
/// contacts (normal + friction cone, render/local_contact_solver.h), and corrected eq. 4.11 is
/// rendered against planes fixed on its bodies. A body stays owned by the local simulation while
/// it stays in the island, so a synchronization moves nothing here (no jump) and the eq. 4.18
/// correction is not needed. EndPeriod reports every island body's end state for the physics
/// half's overwrite (physics::internal::LocalContactPhysics).
class LocalContactHaptic final : public MethodHaptic {
 public:
  /// radius (m), stiffness k (N/m), damping d (N·s/m) of eq. 4.11.
  LocalContactHaptic(double radius, double stiffness, double damping,
                     const render::LocalContactSolverSettings& solver = {});

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  const LocalContactHapticCounters& counters() const { return counters_; }

  /// Several pointers: this half renders its own pointer against `owner`'s island
  /// (null: its own, it is the owner): the owner (pointer 0, ticked first) adopts the island,
  /// every pointer adds its reactions to it, and the half with `steps` (the last pointer, ticked
  /// last) steps it once per tick with all of them and reports its end states. The owner must
  /// outlive the others. Setup only.
  /// Coulomb friction μ at every contact (0, the default: frictionless), as
  /// PointPenaltyHaptic renders it: a stick point per contact on the object, a tangential spring
  /// of the contact's stiffness toward it limited to μ f_n; its reaction goes to the island body
  /// in the same tick. Setup only.
  void SetFriction(double friction) noexcept { friction_ = friction; }

  void ShareIsland(LocalContactHaptic* owner, bool steps) noexcept {
    owner_ = owner;
    steps_ = steps;
  }

  /// The haptic side's island (haptic thread; tests read it between ticks).
  const render::LocalContactSolver& solver() const noexcept { return solver_; }

 private:
  void RenderContacts(const TickInput& in, double alpha, TickOutput* out) noexcept;
  void ContactPlane(std::size_t i, const TickInput& in, double alpha, Vec3* n_W, Vec3* p_WO,
                    Vec3* v_WO, Vec3* p_WCm) noexcept;

  render::LocalContactSolver& island() noexcept { return owner_ ? owner_->solver_ : solver_; }

  /// Maps the snapshot's motions to the island's bodies, or to none while the island holds
  /// another step's model (a follower's snapshot arrived a tick apart from the owner's).
  void MapMotions() noexcept;

  double radius_;
  double stiffness_;
  double damping_;
  double friction_ = 0.0;
  render::PointFrictionAnchors<ir::kMaxPointContacts> anchors_;
  ir::PhysicsSnapshot snapshot_;
  render::LocalContactSolver solver_;
  LocalContactHaptic* owner_ = nullptr;  ///< several pointers: the island's owner
  bool steps_ = true;                    ///< this half steps the island each tick
  std::int64_t adopted_step_ = -2;       ///< snapshot step of the island's model (owner)
  std::int64_t mapped_step_ = -2;        ///< island step local_of_motion_ was mapped against
  std::array<int, ir::kMaxNeighborBodies> local_of_motion_{};
  std::array<Vec3, ir::kMaxPointContacts> n_B_{};  // contact normals in the body frame
  ContactNormals previous_n_{};
  ContactNormals rendered_n_{};
  ir::HapticReport period_;
  // Material vibration at contact onset, added to the rendered force.
  render::ContactTransients transients_;
  LocalContactHapticCounters counters_;
};

}  // namespace mrh::haptic::internal
