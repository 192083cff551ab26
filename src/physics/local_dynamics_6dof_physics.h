// SPDX-License-Identifier: Apache-2.0
// Method `local-dynamics-6dof` (issue 14 item 2): the physics half.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "geometric_ir_builder.h"
#include "mrh/physics/method_physics.h"
#include "mrh/world/contact_export.h"

namespace mrh::physics::internal {

/// Counters of local-dynamics-6dof's physics half (physics thread; read them after the run).
struct LocalDynamics6dofCounters {
  std::int64_t steps = 0;       ///< physics steps
  std::int64_t overwrites = 0;  ///< local states written into the world (eq. 4.16–4.17)
  std::int64_t overwrite_failures = 0;
  int last_island_bodies = 0;    ///< bodies in the latest exported model
  int last_island_contacts = 0;  ///< contact rows in the latest exported model
};

/// Method `local-dynamics-6dof`, physics half. PhysicsStep: (0) every island body of the period
/// just rendered is overwritten with its local end state (eq. 4.16–4.17; a never-pushed island
/// is left to MuJoCo, as in the contact local model), and the period's reaction impulses act as
/// J/Δt^G over the global step; (1) the global step without the user's force (SPEC I10);
/// (2) proxy-6dof's geometric IR (GeometricIrBuilder) for the report's pointer pose; (3) the
/// island of every dynamic body that has a geometric pair — those bodies plus every free body
/// they touch, transitively — with its contact rows (world::ContactExporter), in
/// PhysicsSnapshot::local_model. Its haptic half is haptic::internal::LocalDynamics6dofHaptic.
/// The synchronization logic is the contact local model's (LocalContactPhysics) with the
/// geometric pairs as seeds. Physics thread only; not RT-safe.
class LocalDynamics6dofPhysics final : public MethodPhysics {
 public:
  /// @throws mrh::SceneError from GeometricIrBuilder (a pointer without convex geoms).
  explicit LocalDynamics6dofPhysics(const MethodContext& context);

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;

  /// sync_ms: (0); world_step_ms: (1); ir_ms: (2); model_ms: (3).
  PhaseTimes last_phases() const noexcept override { return phases_; }

  const LocalDynamics6dofCounters& counters() const { return counters_; }

 private:
  void Overwrite(const ir::HapticReport& report);
  void Build(const Pose& X_WP, ir::PhysicsSnapshot* out);
  void Export(ir::PhysicsSnapshot* out);
  void CoastOwned();

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<GeometricIrBuilder> builder_;
  world::ContactExporter exporter_;
  std::vector<int> seeds_, motions_;
  std::vector<int> sent_last_, sent_before_;      // island bodies of the latest two snapshots
  std::vector<int> failed_;                       // bodies the world did not take in this step
  std::vector<int> owned_, owned_before_;         // bodies owned by the local simulation
  std::vector<ir::LocalBodyState> owned_states_;  // their local states taken in this step
  LocalDynamics6dofCounters counters_;
  PhaseTimes phases_;
};

}  // namespace mrh::physics::internal
