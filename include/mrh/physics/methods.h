// SPDX-License-Identifier: Apache-2.0
// The built-in methods' physics halves (the engine's registry pairs them with their haptic halves).
#pragma once

#include <memory>

#include "mrh/physics/method_physics.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/render/virtual_coupling.h"
#include "mrh/settings/settings.h"

namespace mrh::physics {

/// Physics half of "single-rate" (B1) and "impulse" (B4): the period's reaction impulse as a
/// constant force over the step, then the 3-DOF plane IR. Not RT-safe.
std::unique_ptr<MethodPhysics> MakePointPenaltyPhysics(const MethodContext& context);

/// Physics half of "proxy-6dof": the reaction one step late, then the geometric IR.
/// @throws mrh::SceneError for a pointer without convex geoms. Not RT-safe.
std::unique_ptr<MethodPhysics> MakeProxyPhysics(const MethodContext& context);

/// Physics half of "virtual-coupling" (B3): the pointer as a free tool body stepped at the haptic
/// rate under the reported coupling impulse, its weight compensated.
/// @throws mrh::SceneError if the pointer is not a free body. Not RT-safe.
std::unique_ptr<MethodPhysics> MakeVirtualCouplingPhysics(const MethodContext& context);

/// The virtual-coupling gains for the pointer tool of `context`: rendering.coupling_* as given,
/// and an unset rotational gain from the tool, so that its rotation about the weakest principal
/// axis (inertia I_min, kg·m²) has the translational coupling's natural frequency and damping
/// ratio: k_r = k_vc I_min / m_t, b_r = b_vc I_min / m_t (m_t the tool's mass, kg). A stable
/// translational pair therefore gives a stable rotational one. Not RT-safe (setup).
render::CouplingGains ResolveCouplingGains(const MethodContext& context);

/// Physics half of "contact-volume" (B2): the whole scene, pointer included, as one
/// contact-volume penalty simulation at the haptic rate (MuJoCo's contacts off).
/// @throws mrh::SceneError if the world was loaded without world::LoadOptions::
/// penalty_contacts. Not RT-safe.
std::unique_ptr<MethodPhysics> MakeContactVolumePhysics(const MethodContext& context);

/// Physics half of "local-dynamics": overwrite, global step, plane IR and perturbations.
std::unique_ptr<MethodPhysics> MakeLocalDynamicsPhysics(const MethodContext& context);

/// The physics half of `local-dynamics` with the contact local model (rendering.local_model
/// "contact"): the contact island export (world/contact_export.h).
std::unique_ptr<MethodPhysics> MakeLocalContactPhysics(const MethodContext& context);

/// The physics half of `local-dynamics-6dof`: proxy-6dof's geometric IR plus the
/// contact island of every dynamic body with a geometric pair, synchronized as the contact local
/// model. @throws mrh::SceneError from the geometric IR builder. Not RT-safe.
std::unique_ptr<MethodPhysics> MakeLocalDynamics6dofPhysics(const MethodContext& context);

/// True when `local-dynamics` runs the contact model: rendering.local_model is "contact". It
/// simulates free bodies and mechanisms (hinge, slide, ball joints); a mechanism it cannot take
/// is named in MethodPhysics::setup_warnings() and left to the world.
bool UsesContactLocalModel(const MethodContext& context);

/// The rotation weight R_w (m², world frame) proxy-6dof uses for `rendering` (thesis §3.4.1):
/// diag(rendering.rotation_weight) when given, else rotation_weight_scale × the pointer's
/// unit-mass inertia about its body origin, I_O/m = I_Cm/m + |c|²·1 − c cᵀ (c = p_BCm), in the
/// pointer's body axes taken as world axes.
///
/// Why these choices: the renderer's R_w is one constant world-frame matrix and the lever arms
/// r_i are measured from the pointer origin X_WP.p, so the weight that matches its translation
/// weight of 1 is the unit-mass inertia block about that origin; the body axes are used as if the
/// pointer were at its reference orientation (identity), which is exact for an isotropic pointer
/// (the T3.1 cube) and for a pointer held near its reference orientation (the T3.2 stick).
/// @throws mrh::SceneError if the pointer body has no mass (nothing to take an inertia from).
/// @throws mrh::InvalidArgument if its inertia is not positive definite. Not RT-safe.
Mat3 PointerRotationWeight(const world::World& world, int pointer_body,
                           const settings::RenderingSettings& rendering);

/// The proxy renderer's settings for an engine configuration (computed on the setup thread from
/// the world, handed to the haptic half): k_t = stiffness, d_t = damping, k_r = rot_stiffness,
/// d_r = rot_damping, R_w = PointerRotationWeight, μ = friction, max_iterations,
/// tolerance = solver_tolerance.
/// @throws mrh::InvalidArgument naming the session key (rendering.max_iterations above
/// render::kMaxProxyIterations) and the errors of PointerRotationWeight. Not RT-safe.
render::ProxyRendererSettings ProxySettingsFor(const world::World& world, int pointer_body,
                                               const settings::RenderingSettings& rendering);
/// As above for the context's world, pointer and rendering, with max_pair_force from it.
render::ProxyRendererSettings ProxySettingsFor(const MethodContext& context);

/// Every session material must be used: an entry of `rendering.materials` whose name no geom's
/// MJCF `material` attribute carries is a typo.
/// @throws mrh::InvalidArgument "materials.NAME: no geom of the scene uses ..." listing the
/// material names the scene's geoms use. Not RT-safe.
void CheckMaterialsUsed(const world::World& world, const settings::RenderingSettings& rendering);

}  // namespace mrh::physics
