// SPDX-License-Identifier: Apache-2.0
// Projected Gauss–Seidel for the 6-DOF proxy LCP (thesis §3.2.2, eq. 3.4–3.6) in O(m) per sweep.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "mrh/core/spatial.h"

namespace mrh::render {

/// One row of the proxy LCP: the rigid proxy displacement (Δr, Δθ) must move the contact point
/// at lever arm r at least rhs along the unit direction a,
///   a·(Δθ × r + Δr) ≥ rhs                                   (eq. 3.1 / corrected eq. 3.10),
/// and the row contributes f·a to Δr and f·R_w⁻¹(r × a) to Δθ (eq. 3.2–3.3), f ≥ 0.
/// All vectors are in the world frame.
struct ProxyRow {
  Vec3 a = Vec3::UnitZ();  ///< unit row direction: a contact normal n_i or tangent t_i
  Vec3 r = Vec3::Zero();   ///< lever arm v_i − x_p from the pointer origin (m)
  double rhs = 0.0;        ///< depth δ_i (normal row) or σ_i (friction row) (m)
};

/// Iteration budget of the projected Gauss–Seidel solver (thesis §3.2.2 iterates "until f
/// converges" and gives no count: a cap plus a tolerance).
struct ProxySolverSettings {
  /// Sweeps at most (>= 1). Each sweep visits every row once, in order.
  int max_iterations = 50;
  /// The solver stops after the first sweep in which no multiplier changed by more than this
  /// (m, >= 0). 0 runs all max_iterations sweeps unless a sweep changes nothing at all.
  double tolerance = 1e-10;
};

/// What one solve did (every bounded loop reports its work).
struct ProxySolveResult {
  int iterations = 0;       ///< sweeps run
  bool converged = false;   ///< the last sweep's max_change was <= tolerance
  double max_change = 0.0;  ///< max_k |f_k after − f_k before| over the last sweep (m)
};

/// Projected Gauss–Seidel on the proxy LCP w = C f − rhs ≥ 0, f ≥ 0, fᵀw = 0 with
/// C = J W⁻¹ Jᵀ, J's row k = [a_kᵀ, (r_k × a_k)ᵀ], W = diag(I₃, R_w) (eq. 3.4–3.5, 3.7).
///
/// The sweep is eq. 3.6 exactly, but C is never formed: the solver keeps the 6-vector
/// (Δr, Δθ) = W⁻¹Jᵀf and updates it with each row, so row k costs O(1) and a sweep O(m):
///   g_k = R_w⁻¹(r_k × a_k),  c_kk = a_k·a_k + (r_k × a_k)·g_k   (precomputed once per solve),
///   f_k ← max(0, f_k + (rhs_k − a_k·Δr − (r_k × a_k)·Δθ) / c_kk)   (1/c_kk folded into the
///   row data),
///   Δr += (change of f_k)·a_k,  Δθ += (change of f_k)·g_k.
/// Since C f = J (Δr, Δθ), this is the same f as eq. 3.6 up to rounding (tests check 1e-10
/// against SolveProxyDense).
///
/// Convergence: (Δr, Δθ) is unique but f is not when rows are redundant (more than 6, or
/// coplanar contacts); PGS then converges at a rate set by the spread of C's non-zero
/// eigenvalues, roughly |r|²/R_w per sweep for the rotational part, i.e. slowly when R_w ≫ |r|².
///
/// Buffers are sized for `capacity` rows at construction; Solve never allocates.
class ProxySolver {
 public:
  /// @param capacity most rows one Solve accepts (>= 1).
  /// @throws mrh::InvalidArgument if capacity is 0. Not RT-safe (allocates).
  explicit ProxySolver(std::size_t capacity);

  /// Solves for f. On entry `f` holds the starting multipliers (the warm start: the previous
  /// tick's f of the same rows, else zeros); on return the solution. Negative or non-finite
  /// entries of the start are replaced by 0. `dr` and `dtheta` receive Δr (m) and Δθ (rad,
  /// world rotation vector) of eq. 3.2–3.3 for the returned f.
  /// @pre rows.size() == f.size() <= capacity(); every a_k non-zero and every value finite;
  ///      rotation_weight_inverse = R_w⁻¹ symmetric positive definite (m⁻²);
  ///      settings.max_iterations >= 1.
  /// RT-safe.
  ProxySolveResult Solve(std::span<const ProxyRow> rows, const Mat3& rotation_weight_inverse,
                         const ProxySolverSettings& settings, std::span<double> f, Vec3* dr,
                         Vec3* dtheta) noexcept;

  std::size_t capacity() const noexcept { return cache_.size(); }

 private:
  // Per-row data fixed during one solve: a, g = R_w⁻¹(r × a), and a, r × a and rhs divided by
  // c_kk (so a sweep needs no division).
  struct RowCache {
    std::array<double, 3> a;
    std::array<double, 3> g;
    std::array<double, 3> a_scaled;
    std::array<double, 3> j_scaled;
    double rhs_scaled;
  };

  std::array<double, 6> Precompute(std::span<const ProxyRow> rows, const Mat3& w_inv,
                                   std::span<double> f) noexcept;
  double Sweep(std::span<double> f, std::array<double, 6>* state) noexcept;

  std::vector<RowCache> cache_;
};

/// The dense C of eq. 3.5 for `rows`: c_kl = (r_k × a_k)ᵀ R_w⁻¹ (r_l × a_l) + a_kᵀ a_l.
/// Reference and test helper. Not RT-safe (allocates an m × m matrix).
Eigen::MatrixXd ProxyMatrix(std::span<const ProxyRow> rows, const Mat3& rotation_weight_inverse);

/// Reference solver: eq. 3.6 verbatim on the explicit C (O(m²) per sweep), with the same sweep
/// order, start, stopping rule and result as ProxySolver::Solve. It exists so tests can prove
/// the O(m) solver equal to the printed iteration; do not use it for rendering.
/// @pre as ProxySolver::Solve. Not RT-safe (allocates).
ProxySolveResult SolveProxyDense(std::span<const ProxyRow> rows,
                                 const Mat3& rotation_weight_inverse,
                                 const ProxySolverSettings& settings, std::span<double> f);

}  // namespace mrh::render
