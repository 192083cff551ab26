// SPDX-License-Identifier: Apache-2.0
// Settings of the multi-rate engine (the `session` module fills them from a session file).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/device/safety.h"
#include "mrh/settings/choices.h"

namespace mrh::settings {

/// How the two halves are scheduled. Both modes run the same data flow (the timing rule in
/// docs/architecture.md).
enum class Mode {
  kLockstep,  ///< one thread, virtual time, bit-identical on rerun
  kRealtime,  ///< a physics thread and a haptic thread at haptic_dt against the wall clock
};

/// Returns "lockstep" / "realtime".
const char* ModeName(Mode mode) noexcept;

/// The haptic pointer. Session key: `pointer`.
struct PointerSettings {
  std::string body = "pointer";  ///< mocap body of the scene
  /// Sphere radius for 3-DOF rendering (m). 0: take it from the pointer body's sphere geom.
  double radius = 0.0;
};

/// A contact transient (session key `materials.NAME.vibration`): at contact onset with normal
/// approach speed v the user feels Q(t) = a·v·e^(−B t)·sin(2π f t) along the contact normal.
struct VibrationSettings {
  double amplitude = 0.0;  ///< a (N per m/s, >= 0)
  double decay = 0.0;      ///< B (1/s, > 0)
  double frequency = 0.0;  ///< f (Hz, > 0 and below the haptic Nyquist rate 1 / (2 haptic_dt))
};

/// A haptic material (session key `materials.NAME`), given to every scene geom whose MJCF
/// `material` attribute is NAME. An unset gain is the `rendering.*` one.
struct MaterialSettings {
  std::optional<double> stiffness;  ///< N/m
  std::optional<double> damping;    ///< N·s/m
  std::optional<double> friction;   ///< Coulomb μ
  std::optional<VibrationSettings> vibration;
};

/// Rendering parameters. Session key: `rendering`.
struct RenderingSettings {
  double stiffness = 1000.0;  ///< k of eq. 4.11 (N/m)
  double damping = 0.0;       ///< d of eq. 4.11 (N·s/m)
  /// Objects whose signed distance to the pointer is at most this become neighbors (m).
  double neighbor_distance = 0.05;
  /// Broad-phase inflation of the pointer's bounds (m); at least the distance the hand can move
  /// in one physics step.
  double neighbor_margin = 0.05;
  /// Segments per full turn when a sphere, capsule, cylinder or ellipsoid is approximated by a
  /// polyhedron for 6-DOF contact (>= 6). The approximation lies inside the true surface; its
  /// largest gap is r·(1 − cos(π/segments)) (docs/architecture.md).
  int curved_segments = 16;

  // 6-DOF proxy rendering (method proxy-6dof, thesis §3.2.2–3.2.4, §3.4.1).
  /// Rotational spring k_r of eq. 3.8 (N·m/rad).
  double rot_stiffness = 10.0;
  /// Rotational damper d_r of eq. 3.8 (N·m·s/rad); torque_model "thesis" only (must be 0 with
  /// "contact", which damps through the contacts).
  double rot_damping = 0.0;
  /// How the proxy's wrench relates to its contacts (docs/theory.md, "Torque models"):
  /// "contact" (default): R_w = (k_r / k_t)·I, so the rendered wrench is the sum of the proxy's
  /// contact forces and every touched object receives exactly minus its own contacts' forces,
  /// where they act; "thesis": eq. 3.8 with the rotation weight below; the objects receive the
  /// rendered wrench, torque included, which is not a contact wrench (a point contact can be
  /// given a moment), so it is for static worlds (T3.1–T3.5).
  TorqueModel torque_model = TorqueModel::kContact;
  /// Diagonal of the rotation weight R_w (m²), torque_model "thesis" only. Empty: the pointer's
  /// unit-mass inertia times rotation_weight_scale (thesis §3.4.1).
  std::optional<Vec3> rotation_weight;
  /// Multiplier on the unit-mass inertia when rotation_weight is empty (dimensionless, > 0).
  double rotation_weight_scale = 1.0;
  /// Coulomb friction coefficient μ of the friction cones (eq. 3.9–3.10), static = kinetic.
  /// Also single-rate, impulse and local-dynamics: a stick point per contact, 0
  /// frictionless.
  double friction = 0.0;
  /// Proxy solver: "active-set" (exact dual active-set method, the converged answer of the
  /// LCP in a few steps) or "pgs" (the thesis' projected Gauss–Seidel, eq. 3.6, which converges
  /// slowly in rotation when R_w ≫ |r|²).
  ProxySolver proxy_solver = ProxySolver::kActiveSet;
  /// Per tick at most: PGS sweeps, or active-set steps (>= 1).
  int max_iterations = 50;
  /// Tolerance of the proxy solve (m): PGS stops when no multiplier changed more than this in a
  /// sweep; active-set stops when no row is violated by more than this.
  double solver_tolerance = 1e-10;
  /// How the physics step applies proxy-6dof's reaction: "local" (default: a
  /// physics-side proxy run at the haptic rate over the step against the touched objects'
  /// predicted poses, physics::internal::ProxyLocalReaction; stable on light objects at 20 ms)
  /// or "impulse" (the thesis' constant wrench J/Δt^G of the haptic period, §3.5; flings
  /// light objects when k Δt²/I ≳ 1).
  ProxyReaction proxy_reaction = ProxyReaction::kLocal;

  // Local simulation (method local-dynamics, thesis §4.2.2–4.4).
  /// Run the perturbation simulations that measure A and b. false: A from the object's own
  /// mass and inertia and b = 0 (the t4.3 "without perturbations" variant).
  bool perturbation = true;
  /// Test force along −n when the user's last force is zero (N, > 0; Springhead uses 0.5 N).
  double perturbation_force = 0.5;
  /// Local model of local-dynamics: "contact" (default: the neighbors' contact
  /// island, its contacts with the world and each other, normal + Coulomb friction, simulated at
  /// the haptic rate) or "perturbation" (the thesis' accelerance A and bias b, eq. 4.3–4.10).
  LocalModel local_model = LocalModel::kContact;

  // Virtual coupling (B3, Colgate et al. 1995; thesis §1.2.3): the spring–damper between the
  // device pose and the tool.
  double coupling_stiffness = 1000.0;  ///< k_vc (N/m, >= 0)
  double coupling_damping = 10.0;      ///< b_vc (N·s/m, >= 0)
  /// k_vc,r (N·m/rad, >= 0). Unset: k_vc · I_min / m_t, the translational coupling's natural
  /// frequency on the tool's weakest principal axis (physics::ResolveCouplingGains).
  std::optional<double> coupling_rot_stiffness;
  /// b_vc,r (N·m·s/rad, >= 0). Unset: b_vc · I_min / m_t, the translational damping ratio.
  std::optional<double> coupling_rot_damping;
  /// Tool mass m_t (kg, >= 0); 0: the pointer body's MJCF mass.
  double tool_mass = 0.0;
  /// Tool principal inertia (kg·m², body-axes diagonal, each > 0); empty: the MJCF's (scaled
  /// with tool_mass when that is given).
  std::optional<Vec3> tool_inertia;

  /// Haptic materials by MJCF material name (session key `materials`, top level). Empty: every
  /// contact is rendered with the gains above, exactly as without materials.
  std::map<std::string, MaterialSettings> materials;
};

/// One pointer of a session with several (session key `pointers[i]`): its body and
/// radius, and its rendering (the session's `rendering` with the element's overrides applied).
struct PointerLaneSettings {
  PointerSettings pointer;
  RenderingSettings rendering;
};

/// Everything the engine needs besides the world and the device.
struct EngineSettings {
  std::string method = "impulse";
  Mode mode = Mode::kLockstep;
  double physics_dt = 0.05;  ///< s; forced to haptic_dt by single-rate methods
  double haptic_dt = 0.001;  ///< s
  double duration = 10.0;    ///< s of simulated (lockstep) or wall (realtime) time
  PointerSettings pointer;
  RenderingSettings rendering;
  /// Several pointers: every pointer, in order, when there are at least two; their
  /// bodies are distinct mocap bodies and pointers[0] repeats `pointer`. Empty: one pointer,
  /// `pointer` rendered with `rendering`. Pointers never touch each other.
  std::vector<PointerLaneSettings> pointers;
  device::SafetySettings safety;
  /// Ask for SCHED_FIFO + mlockall in real-time mode (a warning, once, if refused).
  bool realtime_priority = true;

  /// @throws mrh::InvalidArgument naming the key: non-finite or non-positive times,
  /// physics_dt not a whole multiple of haptic_dt, negative gains.
  void Validate() const;
  /// Haptic ticks per physics step, n = physics_dt / haptic_dt (rounded).
  int ticks_per_step() const;

  /// Number of pointers: pointers.size() when at least two, else 1.
  int num_pointers() const { return pointers.size() >= 2 ? static_cast<int>(pointers.size()) : 1; }
};

}  // namespace mrh::settings
