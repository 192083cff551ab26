// SPDX-License-Identifier: Apache-2.0
// 6×6 accelerance of a body (contact wrench → body motion) and its estimates compared in T4.6
// (thesis §4.6.3): the thesis' 1 + 18 perturbation runs, its unverified 2-run estimate, an
// analytic one from the constraint solver, and the converged-MuJoCo reference.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>

#include "mrh/core/spatial.h"
#include "mrh/world/world.h"

namespace mrh::world {

/// 6×6 accelerance: u̇ = A w + b, with w = [f; τ] a wrench on the body (N; N·m about its centre
/// of mass, world axes) and u = [v; ω] its COM twist (m/s; rad/s, world axes). Rows 0–2 in
/// m/s² per unit wrench, rows 3–5 in rad/s² per unit wrench.
using Mat66 = Eigen::Matrix<double, 6, 6>;

/// What one estimate cost on the physics thread.
struct EstimateCost {
  int steps = 0;             ///< whole MuJoCo steps (mj_step), each followed by a restore
  int forwards = 0;          ///< forward passes without integration (mj_forward)
  std::int64_t wall_ns = 0;  ///< wall time of the whole estimate (ns)
  /// Of wall_ns, the forward passes' (ns): EstimateAnalytic's forward pass is the one the next
  /// global step does anyway, so a pipeline that shares it pays wall_ns − forward_ns.
  std::int64_t forward_ns = 0;
};

/// An estimate of a body's 6×6 accelerance at the world's current state.
struct AcceleranceEstimate {
  bool ok = false;  ///< false: the method could not estimate here (see each function)
  Mat66 A = Mat66::Zero();
  EstimateCost cost;
  int island_dofs = 0;  ///< EstimateAnalytic: dofs of the body's constraint island
  int active_rows = 0;  ///< EstimateAnalytic: active constraint rows of that island
};

/// Solver settings of the converged reference (MeasureConvergedAccelerance).
struct ConvergedSettings {
  double tolerance = 1e-12;  ///< MuJoCo opt.tolerance for the reference runs
  int iterations = 1000;     ///< opt.iterations
  /// Test wrench per column: ε_f (N) for the force columns, ε_τ (N·m) for the torque columns.
  double epsilon_force = 1e-3;
  double epsilon_torque = 1e-4;
};

/// The body's free-body inverse mass matrix in the coordinates above: blockdiag(I₃/m, I_W⁻¹)
/// with I_W = R I_B Rᵀ its rotational inertia about the COM in world axes at the current pose.
/// @pre `body` is dynamic (mass and inertia > 0). Not RT-safe.
Mat66 FreeBodyInverseMass(const World& world, int body);

/// The converged-MuJoCo reference: central differences of real steps (Newton, settings'
/// tolerance and iteration limit) with ±ε along each wrench axis added to `applied` (the user's
/// wrench at the operating point), A e_k = (u(+) − u(−)) / (2 ε_k Δt). 12 steps; the state is
/// restored exactly. The solver type and settings are put back afterwards. Not RT-safe.
AcceleranceEstimate MeasureConvergedAccelerance(World* world, int body, const Wrench& applied,
                                                const ConvergedSettings& settings = {});

/// The thesis' full 6-DOF estimate (thesis §4.6.3): the zero-force run and 18
/// runs, each of the 3 test forces of eq. 4.5–4.7 (TestForces(f_user), perturbation.h) combined
/// with a torque of ±`torque` (N·m) about each world axis; A is the least-squares fit of
/// y_k = (u_k − u_0)/Δt = A w_k over the 18 wrenches (exact when the response is linear: the
/// wrench matrix has full rank). 19 steps with the model's solver. @pre |f_user| > 0,
/// torque > 0. ok = true. Not RT-safe.
AcceleranceEstimate EstimateFull18(World* world, int body, const Vec3& f_user, double torque);

/// The thesis' unverified cheap estimate (thesis §4.6.3): 2 runs, the zero-force run and one with
/// the user's wrench w. Read here as the symmetric rank-one (SR1) correction of the free-body
/// prior A₀ = FreeBodyInverseMass: with d = A₀ w − y, A = A₀ − d dᵀ / (dᵀ w), which reproduces
/// the measured response (A w = y) and is exact when the constraints that hold the body act in
/// a single direction (A = A₀ − A₀ j jᵀ A₀ / (jᵀ A₀ j + r) for one soft row j). A = A₀ when the
/// body moved freely (|dᵀ w| negligible). 2 steps. @pre w ≠ 0. Not RT-safe.
AcceleranceEstimate EstimateTwoRun(World* world, int body, const Wrench& user);

/// Analytic estimate from the constraint solver, no perturbation runs: one forward pass at the
/// current state with `applied` on the body, the body's constraint island with its active rows
/// at the exact solution (the exact island solve of PerturberSettings::island_solve), and
/// A = J_b (M + J_Aᵀ D_A J_A)⁻¹ J_bᵀ, the island's inverse Hessian of MuJoCo's constraint
/// problem (= M⁻¹ − M⁻¹ J_Aᵀ (J_A M⁻¹ J_Aᵀ + R_A)⁻¹ J_A M⁻¹, the Delassus form) seen through the
/// body's COM Jacobian J_b. The forward pass is the one the next global step would do itself
/// (mj_step = mj_forward + integration), so in a pipeline it costs no extra MuJoCo call.
/// ok = false where the island cannot be solved exactly (more than `max_island_dofs` dofs,
/// elliptic cones, friction loss). The state is restored. Not RT-safe.
AcceleranceEstimate EstimateAnalytic(World* world, int body, const Wrench& applied,
                                     int max_island_dofs = 600);

/// The 3×3 point accelerance (m/s² per N) at r = p − COM (world) from a 6×6 one: Gᵀ A G with
/// G = [I₃; [r]×], the point's acceleration per unit force at the point. RT-safe.
Mat3 PointAccelerance(const Mat66& A, const Vec3& r);

/// ‖S (A − A_ref) S‖_F / ‖S A_ref S‖_F with S = diag(I₃, ℓ I₃): the relative error with the
/// angular rows and torque columns scaled by the length ℓ (m) so that every entry is in 1/kg.
/// RT-safe.
double RelativeError(const Mat66& A, const Mat66& A_ref, double length);

}  // namespace mrh::world
