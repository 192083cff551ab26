// SPDX-License-Identifier: Apache-2.0
// local-dynamics' physics half as experiments and tests see it: options, counters, and the
// perturber's work, read through the public method object (no private header, no cast).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "mrh/physics/method_physics.h"
#include "mrh/world/perturbation.h"

namespace mrh::physics {

/// How the velocity correction of eq. 4.18 (the effect of what A cannot predict) is obtained
/// (thesis §4.4.2, which leaves the computation of f_n open).
enum class CorrectionModel {
  /// Springhead's realization: (u_after − u_before) − b_pred Δt over the global
  /// step. Captures new and broken contacts alike. Relies on the group synchronization (see
  /// LocalDynamicsPhysics): without it, a pushed group's catching up in the global step is
  /// attributed to the neighbor, and a row of k cubes feels like about k²·m.
  kVelocityResidual,
  /// Impulses of the contacts in the global step whose geom pair did not exist where A was
  /// measured, through the body's own M⁻¹J (eq. 4.18's third term): collisions only; broken
  /// contacts reach the local simulation through the next b. Needs the perturbation runs.
  kNewContacts,
};

/// Options of LocalDynamicsPhysics that sessions do not set (tests and experiments do).
struct LocalDynamicsOptions {
  world::PerturberSettings perturber;
  CorrectionModel correction = CorrectionModel::kVelocityResidual;
  /// Accuracy check for experiments and tests: every measurement is repeated by a second
  /// Perturber with these settings at the same state with the same test forces, and the
  /// difference is counted (LocalDynamicsCounters::reference_*). The method still uses the
  /// first measurement.
  std::optional<world::PerturberSettings> reference;
};

/// Wall-clock cost of the phases of a physics step (ms), for cost experiments (t4.3, t4.5).
struct LocalDynamicsTiming {
  double overwrite_ms = 0.0;     ///< (0) overwrite with the local states, group synchronization
  double global_ms = 0.0;        ///< (1) the global step with the f_n bookkeeping
  double ir_ms = 0.0;            ///< (2) neighbor search and plane IR
  double perturbation_ms = 0.0;  ///< (3) perturbation runs (or M⁻¹J)
};

/// Work of the physics half, accumulated over a run (physics thread; read it from that thread,
/// e.g. between lockstep steps, or after the run).
struct LocalDynamicsCounters {
  std::int64_t steps = 0;             ///< PhysicsStep() calls
  std::int64_t perturbed_bodies = 0;  ///< bodies whose A and b were measured, over all steps
  int last_perturbed_bodies = 0;      ///< ... in the latest step (or PhysicsStart)
  std::int64_t overwrites = 0;        ///< local states written into the world (eq. 4.16–4.17)
  /// Local states the body's joints could not represent: the period's reaction impulse was
  /// applied as a force instead, and the local simulation restarts from the global state.
  std::int64_t overwrite_failures = 0;
  std::int64_t own_accelerance = 0;  ///< bodies given M⁻¹J (perturbation off or non-finite)
  /// Group bodies moved along with a synchronized neighbor (see LocalDynamicsPhysics), and those
  /// whose joints could not take the move.
  std::int64_t group_syncs = 0;
  std::int64_t group_sync_failures = 0;
  /// With LocalDynamicsOptions::reference: measurements compared, and the largest and summed
  /// relative difference |A − A_ref| / |A_ref| (Frobenius norms) and |b − b_ref| / (1 + |b_ref|).
  std::int64_t reference_checks = 0;
  double reference_max_rel_A = 0.0;
  double reference_sum_rel_A = 0.0;
  double reference_max_rel_b = 0.0;
  LocalDynamicsTiming last;   ///< the latest step's phases
  LocalDynamicsTiming total;  ///< summed over all steps
};

/// The physics half of "local-dynamics" with the thesis' perturbation model and `options`.
/// @throws as MakeLocalDynamicsPhysics. Not RT-safe.
std::unique_ptr<MethodPhysics> MakeLocalDynamicsPhysics(const MethodContext& context,
                                                        const LocalDynamicsOptions& options);

/// The counters of a perturbation-model local-dynamics physics half, or null for any other
/// method. Physics thread (between lockstep steps, or after the run).
const LocalDynamicsCounters* LocalDynamicsCountersOf(const MethodPhysics& method) noexcept;

/// The perturber's work (solver iterations, runs) of the same, or null for any other method.
const world::PerturberCounters* PerturberCountersOf(const MethodPhysics& method) noexcept;

}  // namespace mrh::physics
