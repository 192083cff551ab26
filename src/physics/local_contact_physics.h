// SPDX-License-Identifier: Apache-2.0
// local-dynamics with the contact local model (rendering.local_model = "contact"):
// the physics half.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "island_sync.h"
#include "mrh/physics/method_physics.h"
#include "mrh/world/contact_export.h"
#include "point_ir_builder.h"

namespace mrh::physics::internal {

using LocalContactCounters = IslandCounters;

/// Method `local-dynamics`, local model "contact" (docs/architecture.md, "The contact local
/// model"), physics half: (0) overwrite every island body of the period just rendered with its
/// local end state (eq. 4.16–4.17, all island bodies, so the group needs no separate
/// synchronization); (1) the global step without the user's force (it enters only through the
/// overwrite); (2) neighbor
/// search and plane IR; (3) export of the island — the dynamic neighbors plus every free body
/// they touch, transitively — with every contact of an island body, found at the step's end
/// state with a 5 mm margin (world/contact_export.h). A body the local simulation owns ends the
/// global step at the local state written in (0) (IslandSync::HoldOwned). Its haptic half,
/// haptic::internal::LocalContactHaptic, simulates the island at 1 kHz. No perturbation runs.
class LocalContactPhysics final : public MethodPhysics {
 public:
  explicit LocalContactPhysics(const MethodContext& context);

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  /// sync_ms: the overwrite (0); world_step_ms: the global step (1); ir_ms: the plane IR (2);
  /// model_ms: the island export (3).
  /// Several pointers (MethodContext::pointers): one world step and ONE island for
  /// all pointers. Every pointer's snapshot carries the union of their neighbor bodies (the same
  /// array, so the same motion indices) and the one island exported from every pointer's
  /// contacts, and only its own contacts. The overwrite takes the island's end states from the
  /// last pointer's report (the haptic half that steps the island) and every pointer's impulses.
  void PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                            std::span<ir::PhysicsSnapshot* const> out) override;
  void PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                           std::span<ir::PhysicsSnapshot* const> out) override;

  std::vector<std::string> setup_warnings() const override { return exporter_.warnings(); }

  PhaseTimes last_phases() const noexcept override { return phases_; }

  const LocalContactCounters& counters() const { return sync_.counters(); }

 private:
  void Export(ir::PhysicsSnapshot* out);
  /// Several pointers: builds every pointer's IR, merges the bodies and exports the island.
  void BuildPointers(std::span<const ir::HapticReport* const> reports,
                     std::span<ir::PhysicsSnapshot* const> out);
  std::vector<int> pointer_bodies_;
  std::vector<PointIrBuilder> builders_;
  std::vector<int> remap_;
  FixedVector<ir::PointContact, ir::kMaxPointContacts> kept_;
  ir::HapticReport merged_;

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<PointIrBuilder> builder_;
  world::ContactExporter exporter_;
  IslandSync sync_;
  std::vector<int> seeds_, motions_;
  PhaseTimes phases_;
};

}  // namespace mrh::physics::internal
