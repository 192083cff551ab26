// SPDX-License-Identifier: Apache-2.0
// The synchronization of a locally simulated contact island (eq. 4.16–4.18), shared by the
// contact local model of `local-dynamics` and by `local-dynamics-6dof`.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mrh/ir/snapshot.h"
#include "mrh/world/contact_export.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

/// The island methods' contact export margin (m, world::ContactExporter).
inline constexpr double kIslandMargin = 0.005;

/// Counters of an island method's physics half (physics thread; read them after the run).
struct IslandCounters {
  std::int64_t steps = 0;       ///< physics steps
  std::int64_t overwrites = 0;  ///< local states written into the world (eq. 4.16–4.17)
  std::int64_t overwrite_failures = 0;
  int last_island_bodies = 0;    ///< bodies in the latest exported model
  int last_island_contacts = 0;  ///< contact rows in the latest exported model
};

/// Which island bodies the local simulation owns, and their states going into and out of the
/// global step. The local simulation owns an island body from the first period in which the
/// pointer pushed the island until the body leaves the island; a never-pushed island is left to
/// MuJoCo and restarts from the world (reset) each period. The local contacts are hard and
/// MuJoCo's are soft, so writing an untouched body's local state into the world moved it off
/// MuJoCo's own resting state every period (a 0.25 mm, 2 mm/s drift of an untouched resting
/// cube). Physics thread only; allocates nothing after construction.
class IslandSync {
 public:
  /// @param world must outlive this object.
  IslandSync(world::World* world, double physics_dt);

  /// eq. 4.16–4.17: every owned island body of the snapshot the report's period rendered takes
  /// its local end state; then the period's reaction acts on every touched body as a force
  /// J/Δt^G during the global step, so that what the owned bodies touch in the world during
  /// the step feels them pushed.
  void Overwrite(const ir::HapticReport& report);

  /// After the global step: every owned body back at the local state written in Overwrite
  /// (`coast_s` = 0), or at that state moved on with its twist for `coast_s` seconds.
  /// The global step's own end state of an owned body is a transient of MuJoCo's soft contacts
  /// at a 20 ms step started from the local hard-contact state (a resting box sinks by up to
  /// 4 mm and pitches by up to 0.08 rad, 3–5 rad/s of spin for one step); exported from there,
  /// the rows of a level local box's raised edge fall outside the margin.
  void HoldOwned(double coast_s);

  /// The island of `seeds` (world body ids; `motions` their snapshot indices) exported into
  /// out->local_model; bodies the world did not take are marked `reset`.
  /// @return the exporter's status bits.
  std::uint32_t Export(world::ContactExporter& exporter, std::span<const int> seeds,
                       std::span<const int> motions, ir::PhysicsSnapshot* out);

  void CountStep() { ++counters_.steps; }

  const IslandCounters& counters() const { return counters_; }

 private:
  // Writes an island body's local state into the world: a free body's as is, a mechanism
  // body's as its joint's coordinates relative to its parent's state in `states` (or the
  // world's, for a parent the island does not hold). Coasts both by `coast_s` first.
  bool Write(const ir::LocalBodyState& state, std::span<const ir::LocalBodyState> states,
             double coast_s);

  world::World* world_;
  double physics_dt_;
  std::vector<int> sent_last_, sent_before_;  // island bodies of the latest two snapshots
  std::vector<int> failed_;                   // bodies the world did not take in this step
  std::vector<int> owned_, owned_before_;     // bodies owned by the local simulation
  std::vector<ir::LocalBodyState> written_;   // local states written in this step's Overwrite
  IslandCounters counters_;
};

}  // namespace mrh::physics::internal
