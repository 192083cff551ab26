// SPDX-License-Identifier: Apache-2.0
// local-dynamics with the contact local model (issue 13, rendering.local_model = "contact").
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "mrh/engine/method.h"
#include "mrh/render/local_contact_solver.h"
#include "mrh/world/contact_export.h"
#include "point_ir_builder.h"

namespace mrh::engine::internal {

/// TickOutput::status bit: a local island body became non-finite and was stopped.
inline constexpr std::uint32_t kLocalIslandFault = 1u << 1;

/// Counters of the contact local model (read them from the thread named, or after the run).
struct LocalContactCounters {
  std::int64_t steps = 0;            ///< physics steps (physics thread)
  std::int64_t overwrites = 0;       ///< local states written into the world (eq. 4.16–4.17)
  std::int64_t overwrite_failures = 0;
  int last_island_bodies = 0;        ///< bodies in the latest exported model
  int last_island_contacts = 0;      ///< contact rows in the latest exported model
  std::int64_t ticks = 0;            ///< haptic ticks (haptic thread)
  std::int64_t local_faults = 0;     ///< non-finite local states (haptic thread)
};

/// Method `local-dynamics`, local model "contact" (docs/architecture.md, "The contact local
/// model"). Physics half: (0) overwrite every island body of the period just rendered with its
/// local end state (eq. 4.16–4.17, all island bodies, so the group needs no separate
/// synchronization); (1) the global step without the user's force (SPEC I10); (2) neighbor
/// search and plane IR; (3) export of the island — the dynamic neighbors plus every free body
/// they touch, transitively — with every contact of an island body, found at the step's end
/// state with a 5 mm margin (world/contact_export.h). Haptic half: the island is simulated at
/// 1 kHz under gravity, the pointer's reaction and its own contacts (normal + friction cone,
/// render/local_contact_solver.h); a body stays owned by the local simulation while it stays in
/// the island, so a synchronization moves nothing on the haptic side (no jump) and the eq. 4.18
/// correction is not needed: the global step's only job for an island body is to find its
/// contacts for the next period. No perturbation runs.
class LocalContactMethod final : public Method {
 public:
  explicit LocalContactMethod(const MethodContext& context,
                              const render::LocalContactSolverSettings& solver = {});

  const char* name() const noexcept override { return "local-dynamics"; }

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  const LocalContactCounters& counters() const { return counters_; }

  /// The haptic side's island (haptic thread; tests read it between ticks).
  const render::LocalContactSolver& solver() const noexcept { return solver_; }

 private:
  // Physics half.
  void Overwrite(const ir::HapticReport& report);
  void Export(ir::PhysicsSnapshot* out);

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<PointIrBuilder> builder_;
  world::ContactExporter exporter_;
  std::vector<int> seeds_, motions_;
  std::vector<int> sent_last_, sent_before_;  // island bodies of the latest two snapshots
  std::vector<int> failed_;                   // bodies the world did not take in this step
  std::vector<int> owned_, owned_before_;     // bodies owned by the local simulation (Overwrite)

  // Haptic half.
  void RenderContacts(const TickInput& in, double alpha, TickOutput* out) noexcept;

  double radius_;
  double stiffness_;
  double damping_;
  ir::PhysicsSnapshot snapshot_;
  render::LocalContactSolver solver_;
  std::array<int, ir::kMaxNeighborBodies> local_of_motion_{};
  std::array<Vec3, ir::kMaxPointContacts> n_B_{};  // contact normals in the body frame
  std::array<Vec3, ir::kMaxPointContacts> previous_n_{};
  std::array<Vec3, ir::kMaxPointContacts> rendered_n_{};
  ir::HapticReport period_;
  LocalContactCounters counters_;
};

/// The "local-dynamics" factory: LocalContactMethod for rendering.local_model "contact", the
/// thesis' LocalDynamicsMethod for "perturbation".
std::unique_ptr<Method> MakeLocalDynamicsAnyModel(const MethodContext& context);

}  // namespace mrh::engine::internal
