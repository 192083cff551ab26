// SPDX-License-Identifier: Apache-2.0
// Exact dual active-set solver (Goldfarb–Idnani) for the 6-DOF proxy problem of thesis §3.2.2.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "mrh/core/spatial.h"
#include "mrh/render/proxy_solver.h"

namespace mrh::render {

/// Solves the same problem as ProxySolver, exactly, in a bounded number of steps.
///
/// The proxy LCP of eq. 3.4–3.5 is the KKT system of a 6-variable quadratic program (its f are
/// the multipliers; docs/theory.md):
///   min ½|Δr|² + ½ Δθᵀ R_w Δθ   s.t.   a_k·(Δθ × r_k + Δr) ≥ rhs_k  for every row k,
/// with the multipliers f_k >= 0 of the rows. (Δr, Δθ) is unique; f is not when rows are
/// redundant. With y = (Δr, Kᵀ⁻¹Δθ), R_w⁻¹ = K Kᵀ, the program is the projection of the origin
/// onto the polyhedron {y : n_k·y ≥ rhs_k}, n_k = (a_k, Kᵀ(r_k × a_k)), and this solver runs
/// the dual method of Goldfarb & Idnani (Math. Programming 27, 1983) on it: start at y = 0 (the
/// unconstrained minimum) with no active rows; repeatedly take the most violated row, step
/// along the part of its normal orthogonal to the active normals, and drop an active row whose
/// multiplier would turn negative. In 6 dimensions at most 6 rows are active, so a step costs
/// one O(m) scan plus O(1) work, and the active set is kept by a re-orthogonalised Gram–Schmidt
/// QR of ≤ 6 columns.
///
/// Why beside PGS: PGS (eq. 3.6, ProxySolver) converges at a rate of about |r|²/R_w per sweep
/// in the rotational directions, which for the thesis' weights (R_w = 3.33–8420 m², |r| ~ 0.1 m)
/// means thousands to millions of sweeps: rotational friction and torque then never converge
/// within a tick. This solver returns the converged (Δr, Δθ) of the same LCP in a handful of
/// steps, and its f satisfies the LCP conditions (f >= 0, C f − rhs >= −tolerance, and
/// complementarity) with at most 6 non-zero entries.
///
/// Cost: the scan reads each row as given (56 bytes) and evaluates its slack as
/// a_k·(Δr + Δθ × r_k) − rhs_k, about 20 flops; the solver stores nothing per row. With a warm
/// start that is already the solution (sustained contact) a Solve is that one scan.
/// Solve never allocates.
class ProxyActiveSetSolver {
 public:
  /// @param capacity most rows one Solve accepts (>= 1).
  /// @throws mrh::InvalidArgument if capacity is 0.
  explicit ProxyActiveSetSolver(std::size_t capacity);

  /// Solves for f and (Δr, Δθ), same contract as ProxySolver::Solve except for the meaning of
  /// the settings and the start:
  /// - settings.max_iterations caps the active-set steps (one step adds or drops one row);
  /// - settings.tolerance (m) is the constraint violation accepted: the solve has converged
  ///   when every row satisfies a_k·(Δθ × r_k + Δr) >= rhs_k − tolerance;
  /// - the start: rows whose entry of `f` is > 0 on entry form the initial active set (a warm
  ///   start from the previous tick's solution); rows whose multipliers come out negative for
  ///   that set are dropped before the iteration starts. Zeros everywhere is a cold start.
  /// result.converged is false if the cap was hit or the rows are infeasible (contradictory
  /// normals); (Δr, Δθ) is then the best point found, still finite.
  /// @pre rows.size() == f.size() <= capacity(); every a_k non-zero, every value finite;
  ///      rotation_weight_inverse symmetric positive definite; settings.max_iterations >= 1.
  /// RT-safe.
  ProxySolveResult Solve(std::span<const ProxyRow> rows, const Mat3& rotation_weight_inverse,
                         const ProxySolverSettings& settings, std::span<double> f, Vec3* dr,
                         Vec3* dtheta) noexcept;

  std::size_t capacity() const noexcept { return capacity_; }

  /// The rows of the last Solve's active set: the only ones whose f may be non-zero (at most 6,
  /// indices into its rows). Valid until the next Solve.
  std::span<const int> active_rows() const noexcept {
    return {active_.data(), static_cast<std::size_t>(count_)};
  }

 private:
  using Vec6 = std::array<double, 6>;
  static constexpr int kDim = 6;

  void SetActiveFromStart(std::span<double> f) noexcept;
  bool Factorize() noexcept;
  void SolveEqualityActive() noexcept;
  int MostViolated(double tolerance, double* violation) const noexcept;
  bool AddRowsUntilFeasible(const ProxySolverSettings& settings, int* steps,
                            double* violation) noexcept;
  bool AddRow(int row, int* steps, int max_steps) noexcept;
  void Project(const Vec6& n_p, std::array<double, kDim>* d, Vec6* z) const noexcept;
  std::array<double, kDim> BackSolve(const std::array<double, kDim>& d) const noexcept;
  double PartialStep(const std::array<double, kDim>& r, int* drop) const noexcept;
  void Activate(int p, double lambda_p, const std::array<double, kDim>& d, const Vec6& z,
                double zz) noexcept;
  void DropActive(int slot) noexcept;
  Vec6 Normal(int row) const noexcept;
  bool IsActive(std::size_t row) const noexcept;

  std::size_t capacity_ = 0;
  std::span<const ProxyRow> rows_;  // during Solve
  // Kᵀ's upper triangle as (K00, K10, K20, K11, K21, K22), R_w⁻¹ = K Kᵀ.
  std::array<double, 6> k_{};

  // Active rows, their multipliers and the QR of their normals: N = Q R, Q 6×count orthonormal
  // columns, R count×count upper triangular.
  std::array<int, kDim> active_{};
  std::array<double, kDim> lambda_{};
  int count_ = 0;
  std::array<Vec6, kDim> q_{};
  std::array<std::array<double, kDim>, kDim> r_{};
  Vec6 y_{};
};

}  // namespace mrh::render
