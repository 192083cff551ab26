// SPDX-License-Identifier: Apache-2.0
// local-dynamics with the contact local model (issue 13, rendering.local_model = "contact"):
// the physics half.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "mrh/physics/method_physics.h"
#include "mrh/world/contact_export.h"
#include "point_ir_builder.h"

namespace mrh::physics::internal {

/// Counters of the contact model's physics half (physics thread; read them after the run).
struct LocalContactCounters {
  std::int64_t steps = 0;            ///< physics steps
  std::int64_t overwrites = 0;       ///< local states written into the world (eq. 4.16–4.17)
  std::int64_t overwrite_failures = 0;
  int last_island_bodies = 0;        ///< bodies in the latest exported model
  int last_island_contacts = 0;      ///< contact rows in the latest exported model
};

/// Method `local-dynamics`, local model "contact" (docs/architecture.md, "The contact local
/// model"), physics half: (0) overwrite every island body of the period just rendered with its
/// local end state (eq. 4.16–4.17, all island bodies, so the group needs no separate
/// synchronization); (1) the global step without the user's force (SPEC I10); (2) neighbor
/// search and plane IR; (3) export of the island — the dynamic neighbors plus every free body
/// they touch, transitively — with every contact of an island body, found at the step's end
/// state with a 5 mm margin (world/contact_export.h). A body the local simulation owns ends the
/// global step at the local state written in (0) (HoldOwnedBodies). Its haptic half,
/// haptic::internal::LocalContactHaptic, simulates the island at 1 kHz. No perturbation runs.
class LocalContactPhysics final : public MethodPhysics {
 public:
  explicit LocalContactPhysics(const MethodContext& context);

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  /// sync_ms: the overwrite (0); world_step_ms: the global step (1); ir_ms: the plane IR (2);
  /// model_ms: the island export (3).
  PhaseTimes last_phases() const noexcept override { return phases_; }

  const LocalContactCounters& counters() const { return counters_; }

 private:
  void Overwrite(const ir::HapticReport& report);
  void Export(ir::PhysicsSnapshot* out);
  void HoldOwnedBodies();

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<PointIrBuilder> builder_;
  world::ContactExporter exporter_;
  std::vector<int> seeds_, motions_;
  std::vector<int> sent_last_, sent_before_;  // island bodies of the latest two snapshots
  std::vector<int> failed_;                   // bodies the world did not take in this step
  std::vector<int> owned_, owned_before_;     // bodies owned by the local simulation (Overwrite)
  std::vector<ir::LocalBodyState> written_;   // local states written in this step's Overwrite
  LocalContactCounters counters_;
  PhaseTimes phases_;
};

}  // namespace mrh::physics::internal
