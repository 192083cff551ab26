// SPDX-License-Identifier: Apache-2.0
// A rendering method: a physics half and an RT haptic half that meet only through ir:: types.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mrh/core/status_bits.h"
#include "mrh/haptic/method_haptic.h"
#include "mrh/physics/method_physics.h"

namespace mrh::engine {

/// A haptic rendering method (single-rate, impulse, local-dynamics, proxy-6dof, ...) as two
/// objects. The physics half (physics::MethodPhysics, module mrh_physics) runs on the physics
/// thread and may use the world; the haptic half (haptic::MethodHaptic, module mrh_haptic,
/// which never links MuJoCo) runs on the haptic thread and is RT-safe. They share no object:
/// data crosses only through the ir::PhysicsSnapshot and ir::HapticReport the engine hands over.
struct Method {
  std::string name;
  /// True if the method needs physics_dt == haptic_dt (the single-rate baseline).
  bool single_rate = false;
  std::unique_ptr<physics::MethodPhysics> physics;
  std::unique_ptr<haptic::MethodHaptic> haptic;
  /// Names of the haptic half's status bits (TickOutput::status), bit i = status_bits[i],
  /// namespaced by the method ("proxy.rows_full"); empty names are unused bits. They reach
  /// RunStats::method_status and summary.json.
  std::vector<std::string> status_bits;
  /// True if the method renders several pointers in one world: its physics half
  /// implements MethodPhysics::PhysicsStepPointers and each pointer gets its own haptic half.
  bool multi_pointer = false;
  /// The haptic halves of pointers 1, 2, ... when the factory links them to `haptic` (several
  /// pointers sharing one local simulation, local-dynamics); empty: the engine builds each
  /// pointer's own half with the method's factory.
  std::vector<std::unique_ptr<haptic::MethodHaptic>> more_haptic = {};
};

/// Builds both halves of a method for one run (setup thread; may throw mrh::InvalidArgument or
/// mrh::SceneError naming the session key at fault).
using MethodFactory = std::function<Method(const physics::MethodContext&)>;

/// One group of a method's status-bit names: the table defined beside the enum whose bits the
/// haptic half sets (e.g. render::kProxyStatusNames), and the prefix that namespaces them in
/// RunStats::method_status ("proxy" gives "proxy.rows_full").
struct StatusBitGroup {
  std::string_view prefix;
  std::span<const StatusBitName> names;
};

/// How session::LoadWorld must load the scene for a method (world::LoadOptions).
struct MethodWorldNeeds {
  /// The pointer body becomes a free body of the world, the tool the method couples the device
  /// to (virtual-coupling), instead of a mocap body.
  bool dynamic_pointer = false;
  /// MuJoCo's own contacts are off: the method computes every contact force itself
  /// (contact-volume).
  bool penalty_contacts = false;
};

/// Which of the session's rendering gains a method reads, and whether it renders a torque. The
/// viewer's panel shows only these gains (so an edit always changes what the user feels); run
/// reports plot a torque only for a method that renders one.
struct MethodSettingsUsed {
  bool stiffness = true;       ///< rendering.stiffness and rendering.damping
  bool friction = false;       ///< rendering.friction
  bool rot_stiffness = false;  ///< rendering.rot_stiffness
  bool coupling = false;       ///< rendering.coupling_stiffness and coupling_damping
  bool torque = false;         ///< the method renders a torque (6-DOF)
};

/// Everything the engine, the CLI (`mrh methods`) and the session parser know of a method.
struct MethodDescriptor {
  std::string name;     ///< session key `method`, e.g. "proxy-6dof"
  std::string summary;  ///< one line for `mrh methods`
  /// The names of TickOutput::status bits, from the tables beside their enums. MakeMethod puts
  /// their expansion (StatusBitNames) into Method::status_bits. Empty: the factory's own
  /// Method::status_bits stand.
  std::vector<StatusBitGroup> status_bits;
  MethodFactory factory;
  MethodWorldNeeds world = {};
  MethodSettingsUsed settings = {};
};

/// Registers a method; a later registration under the same name replaces the earlier one.
/// Thread-safe (setup path: allocates).
void RegisterMethod(MethodDescriptor descriptor);

/// Registers a method without status-bit names (the factory's Method::status_bits stand).
void RegisterMethod(const std::string& name, const std::string& summary, MethodFactory factory);

/// The positional status-bit names of `groups`: element i names bit i ("prefix.name"), "" where
/// no group names the bit; as long as the highest named bit + 1.
std::vector<std::string> StatusBitNames(std::span<const StatusBitGroup> groups);

/// Creates a registered method. @throws mrh::InvalidArgument listing the known names.
Method MakeMethod(const std::string& name, const physics::MethodContext& context);

/// The descriptor of method `name`, or nullopt if none is registered under it.
std::optional<MethodDescriptor> FindMethod(const std::string& name);

/// Every registered method's descriptor, sorted by name.
std::vector<MethodDescriptor> MethodDescriptors();

/// Registered method names with one-line summaries, sorted by name.
std::vector<std::pair<std::string, std::string>> ListMethods();

}  // namespace mrh::engine
