// SPDX-License-Identifier: Apache-2.0
// Method `local-dynamics-6dof`: the physics half.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "geometric_ir_builder.h"
#include "island_sync.h"
#include "mrh/physics/method_physics.h"
#include "mrh/world/contact_export.h"

namespace mrh::physics::internal {

using LocalDynamics6dofCounters = IslandCounters;

/// Method `local-dynamics-6dof`, physics half. PhysicsStep: (0) every island body of the period
/// just rendered is overwritten with its local end state (eq. 4.16–4.17; a never-pushed island
/// is left to MuJoCo, as in the contact local model), and the period's reaction impulses act as
/// J/Δt^G over the global step; (1) the global step without the user's force (it enters only
/// through the overwrite);
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

  /// Several pointers: one geometric IR per pointer, one island for all of them. Pointer 0's
  /// snapshot collects the union of the bodies the pointers' pairs name; every other pointer's
  /// pairs are renumbered into it, and the bodies and the island are copied into every
  /// snapshot. The reports' impulses are summed; the island's end states come from the last
  /// report (the haptic half that steps the island).
  void PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                            std::span<ir::PhysicsSnapshot* const> out) override;
  void PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                           std::span<ir::PhysicsSnapshot* const> out) override;

  /// sync_ms: (0); world_step_ms: (1); ir_ms: (2); model_ms: (3).
  std::vector<std::string> setup_warnings() const override { return exporter_.warnings(); }

  PhaseTimes last_phases() const noexcept override { return phases_; }

  const LocalDynamics6dofCounters& counters() const { return sync_.counters(); }

 private:
  void Build(GeometricIrBuilder& builder, const Pose& X_WP, ir::PhysicsSnapshot* out);
  void Export(ir::PhysicsSnapshot* out);
  void AddSeeds(const ir::PhysicsSnapshot& pairs, const ir::PhysicsSnapshot& bodies);
  void BuildPointers(std::span<const ir::HapticReport* const> reports, double ahead,
                     std::span<ir::PhysicsSnapshot* const> out);

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<GeometricIrBuilder> builder_;
  world::ContactExporter exporter_;
  IslandSync sync_;
  std::vector<int> seeds_, motions_;
  PhaseTimes phases_;
  // Several pointers only: each pointer's body and IR builder, the merged report and the
  // renumbering of one pointer's bodies into pointer 0's.
  std::vector<int> pointer_bodies_;
  std::vector<std::unique_ptr<GeometricIrBuilder>> builders_;
  ir::HapticReport merged_;
  std::vector<int> remap_;
};

}  // namespace mrh::physics::internal
