// SPDX-License-Identifier: Apache-2.0
// The rendering-method strategy: a physics half and an RT haptic half behind one interface.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/engine/settings.h"
#include "mrh/ir/snapshot.h"

namespace mrh::world {
class World;
}

namespace mrh::engine {

/// Input of one haptic tick.
struct TickInput {
  std::int64_t tick = 0;  ///< global tick index
  double t = 0.0;         ///< time of the tick (s)
  int j = 0;              ///< ticks since the current snapshot was adopted (0 at adoption)
  int n = 1;              ///< ticks per physics step
  double dt = 0.001;      ///< haptic period (s)
  Pose X_WP;              ///< pointer (device tool) pose, world frame
  Twist V_WP;             ///< pointer velocity, world frame
};

/// Output of one haptic tick.
struct TickOutput {
  /// Wrench rendered on the user's hand (world frame, torque about the pointer origin), before
  /// the safety layer.
  Wrench w_W;
  /// Proxy pose (world frame). The engine sets it to the pointer pose TickInput::X_WP before
  /// the call; a method with a proxy (proxy-6dof) overwrites it, the others leave it.
  Pose X_WQ;
  int contacts = 0;               ///< active contacts this tick
  std::uint32_t status = 0;       ///< method status bits
};

/// What a method is built from.
struct MethodContext {
  world::World* world = nullptr;  ///< owned by the engine; used only by the physics half
  const EngineSettings* settings = nullptr;
  int pointer_body = -1;
  double pointer_radius = 0.0;    ///< m (3-DOF methods); 0 when neither session nor scene gives it
};

/// The pointer radius a 3-DOF method needs (m, > 0). Only 3-DOF methods ask for it, so a 6-DOF
/// method runs with a pointer that has no sphere geom and no pointer.radius.
/// @throws mrh::SceneError naming pointer.body and pointer.radius when there is none.
double PointerRadiusFor3Dof(const MethodContext& context);

/// A haptic rendering method (single-rate, impulse, local-dynamics, proxy-6dof, ...).
/// The physics half (PhysicsStep) runs on the physics thread and may use the world; the haptic
/// half (Adopt, HapticTick, EndPeriod) runs on the haptic thread, is RT-safe and never touches
/// the world. The two halves share no mutable state: data crosses only through the snapshot and
/// the report the engine hands over.
class Method {
 public:
  virtual ~Method() = default;

  virtual const char* name() const noexcept = 0;

  /// True if the method needs physics_dt == haptic_dt (the single-rate baseline).
  virtual bool single_rate() const noexcept { return false; }

  /// Before the first step: fills the snapshot for haptic period 0 from the initial state
  /// without stepping; `initial` carries the pointer's initial pose. Not RT-safe.
  virtual void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) = 0;

  /// Physics step k: consumes the merged report of haptic period k-1 and fills the snapshot for
  /// period k+1. Not RT-safe.
  virtual void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) = 0;

  /// Haptic thread: a new snapshot becomes current. RT-safe.
  virtual void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept = 0;

  /// Haptic thread: renders one tick. RT-safe.
  virtual void HapticTick(const TickInput& in, TickOutput* out) noexcept = 0;

  /// Haptic thread: moves what this period delivered into `report` and starts a new period.
  /// RT-safe.
  virtual void EndPeriod(ir::HapticReport* report) noexcept = 0;
};

using MethodFactory = std::function<std::unique_ptr<Method>(const MethodContext&)>;

/// Registers a method under a name (later issues add theirs the same way).
void RegisterMethod(const std::string& name, const std::string& summary, MethodFactory factory);

/// Creates a registered method. @throws mrh::InvalidArgument listing the known names.
std::unique_ptr<Method> MakeMethod(const std::string& name, const MethodContext& context);

/// Registered method names with one-line summaries, sorted by name.
std::vector<std::pair<std::string, std::string>> ListMethods();

}  // namespace mrh::engine
