// SPDX-License-Identifier: Apache-2.0
// What the physics side hands to a recorder: physics steps, haptic ticks and snapshots.
#pragma once

#include <cstdint>
#include <string>

#include "mrh/core/spatial.h"
#include "mrh/ir/tick_record.h"

namespace mrh::world {
class World;
}

namespace mrh::ir {
struct PhysicsSnapshot;
}

namespace mrh::physics {

/// One physics step as recorded.
struct StepRecord {
  std::int64_t step = 0;
  double t = 0.0;           ///< simulation time at the end of the step (s)
  double compute_ms = 0.0;  ///< wall time of the physics step (ms)
  int sim_contacts = 0;     ///< MuJoCo contacts
  int neighbors = 0;        ///< neighbor bodies in the snapshot
  int point_contacts = 0;   ///< IR contacts in the snapshot
  int solver_iterations = 0;
  /// The method's phases of this step (MethodPhysics::last_phases), ms.
  double world_step_ms = 0.0, ir_ms = 0.0, model_ms = 0.0, sync_ms = 0.0;
};

/// Receives records on a non-RT thread (the physics thread, or the lockstep loop), in order.
class Recorder {
 public:
  virtual ~Recorder() = default;
  virtual void OnTick(const ir::TickRecord& tick) = 0;
  /// Called after each physics step with the world in its post-step state.
  virtual void OnStep(const StepRecord& step, const world::World& world) = 0;

  /// Called with each snapshot the physics side produces for the haptic thread (the initial one,
  /// then one per physics step, before it is published): the IR the method renders against.
  /// Default: ignored.
  virtual void OnSnapshot(const ir::PhysicsSnapshot& snapshot) { (void)snapshot; }
};

/// Total reaction impulse the pointer delivered to one body over the run (world frame).
struct BodyImpulseTotal {
  int body = -1;
  std::string name;
  Vec3 linear = Vec3::Zero();   ///< N·s
  Vec3 angular = Vec3::Zero();  ///< N·m·s about the COM
};

}  // namespace mrh::physics
