// SPDX-License-Identifier: Apache-2.0
// The physics half of a rendering method: what runs once per physics step with the world.
#pragma once

#include <chrono>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "mrh/ir/snapshot.h"
#include "mrh/settings/settings.h"

namespace mrh::world {
class World;
}

namespace mrh::physics {

/// One pointer of a several-pointer run, for the methods that support them.
struct PointerContext {
  int body = -1;                                           ///< world body id of the mocap pointer
  double radius = 0.0;                                     ///< m (3-DOF methods)
  const settings::RenderingSettings* rendering = nullptr;  ///< the pointer's own gains
};

/// What a method is built from (setup thread).
struct MethodContext {
  world::World* world = nullptr;  ///< owned by the engine; used only by the physics half
  const settings::EngineSettings* settings = nullptr;
  int pointer_body = -1;
  double pointer_radius = 0.0;  ///< m (3-DOF methods); 0 when neither session nor scene gives it
  /// N, the most force one contact pair of a 6-DOF proxy may carry: the device's max_force
  /// (what the user can be shown). Infinite: unbounded.
  double max_pair_force = std::numeric_limits<double>::infinity();
  /// Every pointer when there are at least two (pointers[0] is pointer_body); empty with one.
  /// Only a method registered as supporting several pointers is built with more than one.
  std::vector<PointerContext> pointers = {};
};

/// The pointer radius a 3-DOF method needs (m, > 0): pointer.radius, else the pointer body's
/// sphere geom. Only 3-DOF methods ask for it, so a 6-DOF method runs with a pointer that has no
/// sphere geom and no pointer.radius.
/// @throws mrh::SceneError naming pointer.body and pointer.radius when there is none.
double PointerRadiusFor3Dof(const MethodContext& context);

/// Wall-clock cost of the phases of the latest physics step (ms), for the diagnostics channel
/// (StepRecord, steps.csv, RunStats, summary.json). A phase a method does not have stays 0.
struct PhaseTimes {
  double world_step_ms = 0.0;  ///< the MuJoCo step (mj_step) with its force bookkeeping
  double ir_ms = 0.0;          ///< neighbor search and IR build
  double model_ms = 0.0;       ///< local-model export: perturbation runs (local-dynamics)
  double sync_ms = 0.0;        ///< writing the haptic side's local states back (local-dynamics)
};

/// Wall-clock milliseconds since `t0` (for PhaseTimes).
inline double MsSince(std::chrono::steady_clock::time_point t0) noexcept {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// The physics half of a method. Runs on the physics thread (or the lockstep loop) and may use
/// the world; not RT-safe. It shares no object with its haptic half (haptic::MethodHaptic):
/// it receives the merged ir::HapticReport of a haptic period and fills the ir::PhysicsSnapshot
/// the haptic half renders against.
class MethodPhysics {
 public:
  virtual ~MethodPhysics() = default;

  /// Before the first step: fills the snapshot for haptic period 0 from the initial state
  /// without stepping; `initial` carries the pointer's initial pose.
  virtual void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) = 0;

  /// Physics step k: consumes the merged report of haptic period k-1 and fills the snapshot for
  /// period k+1.
  virtual void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) = 0;

  /// Several pointers: the same as PhysicsStart / PhysicsStep with one report in and
  /// one snapshot out per pointer, in pointer order, over one world step. Only methods built
  /// with MethodContext::pointers override them; the defaults serve pointer 0 alone.
  virtual void PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                                    std::span<ir::PhysicsSnapshot* const> out) {
    PhysicsStart(*initial[0], out[0]);
  }

  virtual void PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                                   std::span<ir::PhysicsSnapshot* const> out) {
    PhysicsStep(*reports[0], out[0]);
  }

  /// The phases of the latest PhysicsStep (or PhysicsStart). Default: none measured.
  virtual PhaseTimes last_phases() const noexcept { return {}; }

  /// The reaction impulses the latest PhysicsStep actually applied (world frame, angular about
  /// each body's COM), when they are not the report's (proxy-6dof with rendering.proxy_reaction
  /// "local"); nullptr (default): the step applied the report's impulses. PhysicsSide's totals
  /// (RunStats::impulses) count these.
  virtual const ir::HapticReport* applied_reaction() const noexcept { return nullptr; }

  /// What the method does not simulate as a user would expect, found at setup (e.g. a
  /// mechanism the local simulation cannot take), one line each; PhysicsSide copies them into
  /// the run's warnings (summary.json). Default: none.
  virtual std::vector<std::string> setup_warnings() const { return {}; }
};

}  // namespace mrh::physics
