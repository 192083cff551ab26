// SPDX-License-Identifier: Apache-2.0
// Physics half of the chapter-3 method `proxy-6dof`: the geometric IR per physics step.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "geometric_ir_builder.h"
#include "mrh/physics/method_physics.h"
#include "proxy_local_reaction.h"

namespace mrh::physics::internal {

using settings::RenderingSettings;

/// The physics half of the chapter-3 method (thesis §3.1–3.2), registered as "proxy-6dof".
///
/// PhysicsStep k: applies the reaction — with rendering.proxy_reaction "impulse", the impulses J
/// of haptic period k−1 as the constant wrench J/Δt^G about each body's COM over this step
/// (the reaction arrives one physics step late, as in thesis §3.5); with "local"
/// (default), the reaction of a physics-side proxy run over the step against the
/// objects' predicted poses (ProxyLocalReaction) — then remembers the poses before the step,
/// steps the world, and builds the geometric IR for the pointer pose of the report
/// (GeometricIrBuilder). PhysicsStart builds from the initial state without stepping. Its haptic
/// half is haptic::internal::ProxyHaptic.
class ProxyPhysics final : public MethodPhysics {
 public:
  /// @throws mrh::SceneError from GeometricIrBuilder (a pointer without convex geoms). Not
  /// RT-safe.
  explicit ProxyPhysics(const MethodContext& context);

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;

  /// Several pointers: every pointer's reaction over one world step (with "local", one
  /// physics-side run of every pointer's proxy against the same objects), then one geometric IR
  /// per pointer. Each snapshot keeps its own bodies: the haptic halves share no state.
  void PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                            std::span<ir::PhysicsSnapshot* const> out) override;
  void PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                           std::span<ir::PhysicsSnapshot* const> out) override;

  PhaseTimes last_phases() const noexcept override { return phases_; }

  const ir::HapticReport* applied_reaction() const noexcept override {
    return local_ ? &local_->applied() : nullptr;
  }

  /// The physics-side reaction ("local" only; nullptr with "impulse"), for tests.
  const ProxyLocalReaction* local_reaction() const { return local_ ? &*local_ : nullptr; }

  /// The work of the last IR build.
  const GeometricIrStats& ir_stats() const { return builder_->stats(); }

 private:
  void Build(GeometricIrBuilder& builder, const Pose& X_WP, ir::PhysicsSnapshot* out);

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  PhaseTimes phases_;
  std::optional<GeometricIrBuilder> builder_;
  std::optional<ProxyLocalReaction> local_;
  // Several pointers only: each pointer's body and IR builder.
  std::vector<int> pointer_bodies_;
  std::vector<std::unique_ptr<GeometricIrBuilder>> builders_;
};

}  // namespace mrh::physics::internal
