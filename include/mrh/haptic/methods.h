// SPDX-License-Identifier: Apache-2.0
// The built-in methods' haptic halves, built from plain parameters (they never see the world).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "mrh/core/status_bits.h"
#include "mrh/haptic/method_haptic.h"
#include "mrh/render/local_contact_solver.h"
#include "mrh/render/penalty_sum.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/render/virtual_coupling.h"

namespace mrh::haptic {

/// TickOutput::status bits of local-dynamics' haptic half (RunStats::method_status names them
/// "local_dynamics.<name>"). proxy-6dof reports render::ProxyStatusBits ("proxy.<name>").
enum LocalDynamicsStatusBits : std::uint32_t {
  kLocalBodyFault = 1u << 0,  ///< a local body's state became non-finite and was stopped
};

/// The names of LocalDynamicsStatusBits.
inline constexpr std::array<StatusBitName, 1> kLocalDynamicsStatusNames{{
    {kLocalBodyFault, "local_body_fault"},
}};
static_assert(ValidStatusBitNames(kLocalDynamicsStatusNames));

/// Haptic half of "single-rate" and "impulse": 3-DOF penalty (eq. 4.11) with a pointer sphere
/// of `radius` (m), stiffness k (N/m) and damping d (N·s/m), and Coulomb friction μ at each
/// contact when `friction` > 0 (0: frictionless). Not RT-safe (allocates
/// once).
std::unique_ptr<MethodHaptic> MakePointPenaltyHaptic(double radius, double stiffness,
                                                     double damping, double friction = 0.0);

/// Haptic half of "proxy-6dof": the 6-DOF proxy with `settings` (physics::ProxySettingsFor).
std::unique_ptr<MethodHaptic> MakeProxyHaptic(const render::ProxyRendererSettings& settings);

/// Haptic half of "penalty-sum" (B5): per-contact springs on the interpolated geometric IR.
/// TickOutput::status carries render::kProxyStatusBadInput on non-finite input.
std::unique_ptr<MethodHaptic> MakePenaltySumHaptic(const render::PenaltySumSettings& settings);

/// Status bit of "virtual-coupling"'s haptic half: the coupling wrench was not finite (zero
/// output this tick).
inline constexpr std::uint32_t kVirtualCouplingBadInput = 1u << 0;
inline constexpr std::array<StatusBitName, 1> kVirtualCouplingStatusNames{{
    {kVirtualCouplingBadInput, "bad_input"},
}};
static_assert(ValidStatusBitNames(kVirtualCouplingStatusNames));

/// Haptic half of "virtual-coupling" (B3): the spring–damper to the tool of the snapshot.
std::unique_ptr<MethodHaptic> MakeVirtualCouplingHaptic(const render::CouplingGains& gains);

/// Status bit of "contact-volume"'s haptic half: the snapshot's pointer wrench was not finite
/// (zero output this tick).
inline constexpr std::uint32_t kContactVolumeBadInput = 1u << 0;
inline constexpr std::array<StatusBitName, 1> kContactVolumeStatusNames{{
    {kContactVolumeBadInput, "bad_input"},
}};
static_assert(ValidStatusBitNames(kContactVolumeStatusNames));

/// Haptic half of "contact-volume" (B2): displays the penalty wrench on the pointer that the
/// newest snapshot carries (ir::PhysicsSnapshot::pointer_wrench_W). RT-safe after construction.
std::unique_ptr<MethodHaptic> MakeContactVolumeHaptic();

/// Haptic half of "local-dynamics": local simulation of the neighbors, 3-DOF penalty as above.
std::unique_ptr<MethodHaptic> MakeLocalDynamicsHaptic(double radius, double stiffness,
                                                      double damping);

/// Haptic half of "local-dynamics" with the contact local model: the snapshot's contact island
/// simulated at the haptic rate (render/local_contact_solver.h) under the pointer's penalty
/// force (radius m, stiffness N/m, damping N·s/m). RT-safe after construction.
std::unique_ptr<MethodHaptic> MakeLocalContactHaptic(double radius, double stiffness,
                                                     double damping, double friction = 0.0);

/// One pointer's gains for a group of haptic halves (radius m, stiffness N/m, damping N·s/m).
struct PointerGains {
  double radius = 0.0;
  double stiffness = 0.0;
  double damping = 0.0;
  double friction = 0.0;  ///< Coulomb μ (0: frictionless)
};

/// Several pointers: one haptic half of "local-dynamics" (contact local model) per
/// pointer, in pointer order, all rendering against one island: pointer 0's half adopts it, each
/// adds its reactions, and the last one (ticked last) steps it once per tick with every
/// pointer's force. Keep them alive together, pointer 0's last. Not RT-safe (allocates once).
std::vector<std::unique_ptr<MethodHaptic>> MakeLocalContactHapticGroup(
    const std::vector<PointerGains>& pointers);

/// Status bit of "local-dynamics-6dof"'s haptic half beyond render::ProxyStatusBits: a local
/// body's state became non-finite and was stopped.
inline constexpr std::uint32_t kLocalDynamics6dofBodyFault = 1u << 3;
inline constexpr std::array<StatusBitName, 1> kLocalDynamics6dofStatusNames{{
    {kLocalDynamics6dofBodyFault, "local_body_fault"},
}};
static_assert(ValidStatusBitNames(kLocalDynamics6dofStatusNames));
static_assert((kLocalDynamics6dofBodyFault &
               (render::kProxyStatusRowsFull | render::kProxyStatusNotConverged |
                render::kProxyStatusBadInput | render::kProxyStatusPairForceLimited)) == 0);

/// Haptic half of "local-dynamics-6dof": the 6-DOF proxy with `settings`
/// (physics::ProxySettingsFor) against planes riding on the snapshot's contact island, simulated
/// at the haptic rate; the proxy's reaction pushes the island in the same tick. TickOutput::status
/// carries render::ProxyStatusBits plus bit 3 (a local body became non-finite). RT-safe after
/// construction. @throws mrh::InvalidArgument from settings.Validate().
std::unique_ptr<MethodHaptic> MakeLocalDynamics6dofHaptic(
    const render::ProxyRendererSettings& settings);

/// Several pointers: one haptic half of "local-dynamics-6dof" per pointer (its own proxy
/// settings, physics::ProxySettingsFor of that pointer), in pointer order, all rendering against
/// one island: pointer 0's half adopts it, each re-poses its planes on it and adds its
/// reactions, and the last one (ticked last) steps it once per tick with every pointer's
/// reactions. Keep them alive together, pointer 0's last. Not RT-safe (allocates once).
/// @throws mrh::InvalidArgument from a settings.Validate().
std::vector<std::unique_ptr<MethodHaptic>> MakeLocalDynamics6dofHapticGroup(
    const std::vector<render::ProxyRendererSettings>& pointers);

/// proxy-6dof's haptic half: the renderer's output of its latest tick, and the tick IR it
/// rendered against; null when `method` is not proxy-6dof's. Haptic thread (or between
/// lockstep ticks). RT-safe.
const render::ProxyOutput* ProxyLastOutput(const MethodHaptic& method) noexcept;
const render::TickIr* ProxyLastTickIr(const MethodHaptic& method) noexcept;

/// local-dynamics-6dof's haptic half: the renderer's output of its latest tick, the re-posed
/// tick IR and the local island; null when `method` is not local-dynamics-6dof's. Haptic thread
/// (or between lockstep ticks). RT-safe.
const render::ProxyOutput* LocalDynamics6dofLastOutput(const MethodHaptic& method) noexcept;
const render::TickIr* LocalDynamics6dofLastTickIr(const MethodHaptic& method) noexcept;
const render::LocalContactSolver* LocalDynamics6dofSolver(const MethodHaptic& method) noexcept;

}  // namespace mrh::haptic
