// SPDX-License-Identifier: Apache-2.0
// The key tables of the session format: one row per settings field (key, member, unit, doc).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "mrh/device/device.h"
#include "mrh/device/safety.h"
#include "mrh/device/simulated.h"
#include "mrh/settings/settings.h"

namespace mrh::session::internal {

/// A session key that maps straight onto a member of the settings struct S. Adding a plain
/// number or flag to a block is one row in its table below (and one row in
/// docs/session-format.md, which a test checks).
template <typename S>
struct Field {
  std::string_view key;
  std::variant<double S::*, int S::*, bool S::*, std::string S::*, std::optional<double> S::*,
               settings::TorqueModel S::*, settings::ProxySolver S::*, settings::ProxyReaction S::*,
               settings::LocalModel S::*>
      member;
  std::string_view unit;  ///< SI unit of a number, for messages ("" for flags and strings)
  std::string_view doc;   ///< one line, for readers of this table
};

/// Top-level keys stored in engine::EngineSettings.
inline constexpr std::array<Field<settings::EngineSettings>, 5> kEngineFields{{
    {"method", &settings::EngineSettings::method, "", "rendering method name"},
    {"physics_dt", &settings::EngineSettings::physics_dt, "s", "physics (global) step period"},
    {"haptic_dt", &settings::EngineSettings::haptic_dt, "s", "haptic tick period"},
    {"duration", &settings::EngineSettings::duration, "s", "length of the run"},
    {"realtime_priority", &settings::EngineSettings::realtime_priority, "",
     "ask for SCHED_FIFO + mlockall in real-time mode"},
}};

/// `pointer` block.
inline constexpr std::array<Field<settings::PointerSettings>, 2> kPointerFields{{
    {"body", &settings::PointerSettings::body, "", "mocap body of the scene that is the pointer"},
    {"radius", &settings::PointerSettings::radius, "m", "sphere radius; 0: from the body's geom"},
}};

/// `rendering` block.
inline constexpr std::array<Field<settings::RenderingSettings>, 22> kRenderingFields{{
    {"stiffness", &settings::RenderingSettings::stiffness, "N/m", "penalty spring k (eq. 4.11)"},
    {"damping", &settings::RenderingSettings::damping, "N*s/m", "penalty damper d (eq. 4.11)"},
    {"neighbor_distance", &settings::RenderingSettings::neighbor_distance, "m",
     "objects this close to the pointer become neighbors"},
    {"neighbor_margin", &settings::RenderingSettings::neighbor_margin, "m",
     "broad-phase inflation of the pointer's bounds"},
    {"curved_segments", &settings::RenderingSettings::curved_segments, "",
     "segments per turn of polyhedral spheres, capsules, cylinders, ellipsoids"},
    {"rot_stiffness", &settings::RenderingSettings::rot_stiffness, "N*m/rad",
     "proxy rotational spring k_r (eq. 3.8)"},
    {"rot_damping", &settings::RenderingSettings::rot_damping, "N*m*s/rad",
     "proxy rotational damper d_r (eq. 3.8)"},
    {"rotation_weight_scale", &settings::RenderingSettings::rotation_weight_scale, "",
     "multiplier on the pointer's unit-mass inertia for R_w"},
    {"friction", &settings::RenderingSettings::friction, "", "friction coefficient mu"},
    {"torque_model", &settings::RenderingSettings::torque_model, "",
     "6-DOF: \"thesis\" (eq. 3.8, default) or \"contact\" (every force a contact force)"},
    {"proxy_solver", &settings::RenderingSettings::proxy_solver, "",
     "\"active-set\" (exact) or \"pgs\" (thesis eq. 3.6)"},
    {"max_iterations", &settings::RenderingSettings::max_iterations, "",
     "proxy solver sweeps (pgs) or steps (active-set) per tick at most"},
    {"solver_tolerance", &settings::RenderingSettings::solver_tolerance, "m",
     "proxy solver tolerance: multiplier change (pgs) or row violation (active-set)"},
    {"proxy_reaction", &settings::RenderingSettings::proxy_reaction, "",
     "proxy-6dof reaction in the physics step: \"local\" (default) or \"impulse\" (J/dt)"},
    {"perturbation", &settings::RenderingSettings::perturbation, "",
     "measure A and b by perturbation simulations (local-dynamics)"},
    {"perturbation_force", &settings::RenderingSettings::perturbation_force, "N",
     "test force when the user's last force is zero"},
    {"local_model", &settings::RenderingSettings::local_model, "",
     "local-dynamics: \"contact\" (island with friction, default) or \"perturbation\" (A, b)"},
    {"coupling_stiffness", &settings::RenderingSettings::coupling_stiffness, "N/m",
     "virtual-coupling spring k_vc"},
    {"coupling_damping", &settings::RenderingSettings::coupling_damping, "N*s/m",
     "virtual-coupling damper b_vc"},
    {"coupling_rot_stiffness", &settings::RenderingSettings::coupling_rot_stiffness, "N*m/rad",
     "virtual-coupling rotational spring; unset: k_vc I_min / m_t"},
    {"coupling_rot_damping", &settings::RenderingSettings::coupling_rot_damping, "N*m*s/rad",
     "virtual-coupling rotational damper; unset: b_vc I_min / m_t"},
    {"tool_mass", &settings::RenderingSettings::tool_mass, "kg",
     "virtual-coupling tool mass; 0: the pointer body's"},
}};

/// `materials.NAME` block (every key optional; unset gains are the rendering.* ones).
inline constexpr std::array<Field<settings::MaterialSettings>, 3> kMaterialFields{{
    {"stiffness", &settings::MaterialSettings::stiffness, "N/m", "spring k of this material"},
    {"damping", &settings::MaterialSettings::damping, "N*s/m", "damper d of this material"},
    {"friction", &settings::MaterialSettings::friction, "", "Coulomb mu of this material"},
}};

/// `materials.NAME.vibration` block (all three keys required).
inline constexpr std::array<Field<settings::VibrationSettings>, 3> kVibrationFields{{
    {"amplitude", &settings::VibrationSettings::amplitude, "N*s/m", "a: N per m/s of impact"},
    {"decay", &settings::VibrationSettings::decay, "1/s", "B: decay rate of the transient"},
    {"frequency", &settings::VibrationSettings::frequency, "Hz", "f: frequency of the transient"},
}};

/// `rendering` keys the parser handles itself (not plain fields).
inline constexpr std::array<std::string_view, 2> kRenderingSpecialKeys{
    {"rotation_weight", "tool_inertia"}};

/// `safety` block.
inline constexpr std::array<Field<device::SafetySettings>, 5> kSafetyFields{{
    {"ramp", &device::SafetySettings::ramp, "", "engage ramp on/off"},
    {"ramp_time", &device::SafetySettings::ramp_time, "s", "engage ramp length"},
    {"watchdog_timeout", &device::SafetySettings::watchdog_timeout, "s",
     "physics silence before the output fades"},
    {"watchdog_fade", &device::SafetySettings::watchdog_fade, "s", "fade-out length"},
    {"max_body_speed", &device::SafetySettings::max_body_speed, "m/s",
     "a free body faster than this ends the run as diverged (0: no speed test)"},
}};

/// `device.hand` block.
inline constexpr std::array<Field<device::HandSettings>, 6> kHandFields{{
    {"mass", &device::HandSettings::mass, "kg", "effective mass of hand + grip"},
    {"stiffness", &device::HandSettings::stiffness, "N/m", "pull toward the target"},
    {"damping", &device::HandSettings::damping, "N*s/m", "linear damping"},
    {"inertia", &device::HandSettings::inertia, "kg*m^2", "isotropic rotational inertia"},
    {"rot_stiffness", &device::HandSettings::rot_stiffness, "N*m/rad", "rotational pull"},
    {"rot_damping", &device::HandSettings::rot_damping, "N*m*s/rad", "rotational damping"},
}};

/// `device.limits` block (overrides of the device's specifications; each must be > 0).
inline constexpr std::array<Field<device::Specifications>, 3> kLimitFields{{
    {"max_force", &device::Specifications::max_force, "N", "force clamp"},
    {"max_torque", &device::Specifications::max_torque, "N*m", "torque clamp"},
    {"max_stiffness", &device::Specifications::max_stiffness, "N/m", "largest stable stiffness"},
}};

/// Keys the parser handles itself (not plain fields), top level. `psychophysics` is read and
/// validated by mrh::psychophysics::LoadStudy (docs/psychophysics.md); sessions ignore it.
inline constexpr std::array<std::string_view, 8> kTopLevelSpecialKeys{
    {"scene", "mode", "keyframe", "gravity", "device", "psychophysics", "materials", "pointers"}};

/// Top-level blocks made only of fields (kPointerFields, kRenderingFields, kSafetyFields).
inline constexpr std::array<std::string_view, 3> kTopLevelBlocks{
    {"pointer", "rendering", "safety"}};

/// `device` keys every device type accepts.
inline constexpr std::array<std::string_view, 4> kDeviceCommonKeys{
    {"type", "model", "limits", "calibration"}};

/// `device.limits` keys the parser handles itself (not plain fields of Specifications).
inline constexpr std::array<std::string_view, 2> kLimitSpecialKeys{
    {"workspace_radius", "output_dof"}};

/// A device type and the keys only it accepts (empty slots unused).
struct DeviceType {
  std::string_view name;
  std::array<std::string_view, 3> keys;
};

inline constexpr std::array<DeviceType, 8> kDeviceTypes{{
    {"fixed", {"pose"}},
    {"scripted", {"keyframes", "trajectory"}},
    {"hand", {"keyframes", "trajectory", "hand"}},
    {"replay", {"replay"}},
    {"external", {}},  // fed by the caller's servo loop (Engine::Start/Tick/Stop)
    {"forcedimension", {"library", "id"}},  // DHD library loaded at run time
    {"openhaptics", {"library", "name"}},   // HD library loaded at run time
    {"udp", {"bind", "timeout", "fade"}},   // poses in, wrenches out over UDP
}};

/// `device.calibration` keys.
inline constexpr std::array<std::string_view, 3> kCalibrationKeys{
    {"position", "orientation", "scale"}};

}  // namespace mrh::session::internal
