// SPDX-License-Identifier: Apache-2.0
// Physics half of the Chapter-4 method: the dynamic IR (accelerance + bias) per physics step.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "mrh/physics/local_dynamics.h"
#include "mrh/physics/method_physics.h"
#include "mrh/world/perturbation.h"
#include "point_ir_builder.h"

namespace mrh::physics::internal {

using physics::CorrectionModel;
using physics::LocalDynamicsCounters;
using physics::LocalDynamicsOptions;
using physics::LocalDynamicsTiming;

using settings::RenderingSettings;

/// Method `local-dynamics` (thesis ch. 4): the physics half overwrites the neighbors with the local
/// states of the previous period (eq. 4.16–4.17) and moves the rest of each neighbor's contact
/// group along with it (below), steps the world recording the velocity
/// correction f_n (eq. 4.18, see CorrectionModel), builds the plane IR and
/// measures every dynamic neighbor's A and b by perturbation simulations (eq. 4.3–4.10, a
/// shared zero-force run). The haptic half simulates each dynamic neighbor locally
/// (eq. 4.13–4.15) and renders corrected eq. 4.11 against planes that move with it, feeding the
/// reaction (eq. 4.12) to the local simulation in the same tick.
///
/// [EXTENSION of thesis §4.4.1] Group synchronization. A, measured with the whole world, makes the
/// local body move as its contact group would (a pushed row of k cubes feels like k·m), but
/// eq. 4.16–4.17 write only the neighbor back: the rest of the group never receives the user's
/// push, lags, and the global step then brakes the neighbor (or, with soft contacts, kicks the
/// group ahead). So the neighbor's local − global discrepancy Δ (twist, and COM position plus
/// rotation vector) is mapped onto every other group body j that is not itself locally simulated:
/// Δ_j = A_jB A_B⁺ Δ, with A_jB the cross accelerance from the same perturbation runs. In the
/// linear model Δ = A_B (∫f, ∬f) exactly, so this gives j the state the user's force would have
/// given it. Neighbors in one group still do not couple to each other (each neighbor's A maps
/// only the force on itself).
///
/// The world is overwritten with the state the next period starts from: the local end state
/// plus the eq. 4.18 correction sent for that period's first tick. (Writing the bare end state
/// lets the global and local states drift apart by that correction, and the loop through b then
/// turns unstable on stiff contacts: a cube resting on a floor starts to bounce.)
///
/// This is the physics half; the haptic half is haptic::internal::LocalDynamicsHaptic.
class LocalDynamicsPhysics final : public MethodPhysics {
 public:
  explicit LocalDynamicsPhysics(const MethodContext& context,
                                const LocalDynamicsOptions& options = {});

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;

  /// counters().last as the engine's phases: overwrite → sync, global → world_step, ir,
  /// perturbation → model.
  PhaseTimes last_phases() const noexcept override {
    const LocalDynamicsTiming& t = counters_.last;
    return PhaseTimes{t.global_ms, t.ir_ms, t.perturbation_ms, t.overwrite_ms};
  }

  const LocalDynamicsCounters& counters() const { return counters_; }

  const world::PerturberCounters& perturber_counters() const { return perturber_.counters(); }

 private:
  // A dynamic neighbor in a snapshot this half produced.
  struct SentBody {
    int body = -1;
    ir::Mat63 A = ir::Mat63::Zero();  // accelerance it was sent with
    Vec6 b = Vec6::Zero();            // bias it was sent with (b_pred of the next step)
    std::size_t first_member = 0;     // its group: [first_member, + members) of the group list
    std::size_t members = 0;
    Twist u_before;  // COM twist before the global step that follows
    Twist dV_n;      // eq. 4.18 correction from that step
    Twist dV_sent;   // the correction this snapshot carried (applied at its tick 0)
  };

  // A neighbor to measure in this step.
  struct Target {
    std::size_t motion = 0;   // index into the snapshot's bodies
    int contact = -1;         // its nearest contact
    Vec3 p_W = Vec3::Zero();  // test-force point (the contact's plane point), world
    Vec3 f1 = Vec3::Zero();   // first test force (eq. 4.5–4.7)
  };

  void Overwrite(const ir::HapticReport& report);
  void SyncGroup(const SentBody& sent, const world::BodyState& global,
                 const ir::LocalBodyState& local);
  void GlobalStep(const ir::HapticReport& report);
  void FindTargets(const ir::HapticReport* report, const ir::PhysicsSnapshot& out);
  void MeasureTargets(ir::PhysicsSnapshot* out);
  void CheckAgainstReference();
  void FillDynamics(ir::PhysicsSnapshot* out);
  world::DynamicIr OwnAccelerance(int body, const Vec3& p_W) const;
  const SentBody* FindSent(const std::vector<SentBody>& sent, int body) const;

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  settings::RenderingSettings rendering_;
  CorrectionModel correction_;
  std::optional<PointIrBuilder> builder_;
  world::Perturber perturber_;
  std::optional<world::Perturber> reference_;
  std::vector<SentBody> sent_last_;    // dynamic bodies of the latest snapshot (rendered next)
  std::vector<SentBody> sent_before_;  // ... of the one before (rendered by the report's period)
  std::vector<world::GroupResponse> group_last_;    // groups of sent_last_
  std::vector<world::GroupResponse> group_before_;  // groups of sent_before_
  std::vector<world::GroupResponse> measured_groups_;
  std::vector<std::size_t> measured_group_start_;
  std::vector<int> sync_failed_;  // bodies whose overwrite failed in this step
  std::vector<Target> targets_;
  std::vector<int> target_bodies_;
  std::vector<world::DynamicIr> measured_;
  std::vector<std::uint64_t> known_contacts_;  // contact pairs where the latest A was measured
  LocalDynamicsCounters counters_;
};

}  // namespace mrh::physics::internal
