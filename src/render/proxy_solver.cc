// SPDX-License-Identifier: Apache-2.0
// Projected Gauss–Seidel for the proxy LCP: O(m) sweeps on (Δr, Δθ) and the dense reference.
#include "mrh/render/proxy_solver.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "mrh/core/assert.h"
#include "mrh/core/error.h"

namespace mrh::render {
namespace {

// A start value the solver can use: finite and non-negative (the LCP's feasible cone).
double ClampStart(double value) noexcept {
  return std::isfinite(value) && value > 0.0 ? value : 0.0;
}

}  // namespace

ProxySolver::ProxySolver(std::size_t capacity) {
  if (capacity == 0) {
    throw InvalidArgument(
        "ProxySolver: capacity = 0 rows; expected >= 1; pass the most constraint rows one tick "
        "can have (2 per contact point with friction)");
  }
  cache_.resize(capacity);
}

ProxySolveResult ProxySolver::Solve(std::span<const ProxyRow> rows,
                                    const Mat3& rotation_weight_inverse,
                                    const ProxySolverSettings& settings, std::span<double> f,
                                    Vec3* dr, Vec3* dtheta) noexcept {
  MRH_ASSERT(rows.size() == f.size() && rows.size() <= cache_.size());
  MRH_ASSERT(settings.max_iterations >= 1);
  const std::size_t m = std::min(rows.size(), cache_.size());
  std::array<double, 6> u = Precompute(rows.first(m), rotation_weight_inverse, f);

  ProxySolveResult result;
  if (m == 0) result.converged = true;
  for (int sweep = 0; m > 0 && sweep < settings.max_iterations; ++sweep) {
    result.iterations = sweep + 1;
    result.max_change = Sweep(f.first(m), &u);
    if (result.max_change <= settings.tolerance) {
      result.converged = true;
      break;
    }
  }
  *dr = Vec3(u[0], u[1], u[2]);
  *dtheta = Vec3(u[3], u[4], u[5]);
  return result;
}

// Row data fixed during the solve, and (Δr, Δθ) = W⁻¹Jᵀf of the start (eq. 3.2–3.3). Written
// out on plain doubles: this loop and Sweep are the whole cost of a large contact set.
std::array<double, 6> ProxySolver::Precompute(std::span<const ProxyRow> rows, const Mat3& w_inv,
                                              std::span<double> f) noexcept {
  std::array<double, 6> u{};
  for (std::size_t k = 0; k < rows.size(); ++k) {
    RowCache& c = cache_[k];
    const Vec3& a = rows[k].a;
    const Vec3& r = rows[k].r;
    const std::array<double, 3> j = {r.y() * a.z() - r.z() * a.y(), r.z() * a.x() - r.x() * a.z(),
                                     r.x() * a.y() - r.y() * a.x()};  // r × a
    for (std::size_t i = 0; i < 3; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      c.a[i] = a[row];
      c.g[i] = w_inv(row, 0) * j[0] + w_inv(row, 1) * j[1] + w_inv(row, 2) * j[2];
    }
    // c_kk = a·a + jᵀR_w⁻¹j >= a·a > 0 for SPD R_w (eq. 3.5 diagonal).
    const double ckk = (a.x() * a.x() + a.y() * a.y() + a.z() * a.z()) +
                       (j[0] * c.g[0] + j[1] * c.g[1] + j[2] * c.g[2]);
    MRH_ASSERT(ckk > 0.0);
    const double inv = 1.0 / ckk;
    for (std::size_t i = 0; i < 3; ++i) {
      c.a_scaled[i] = c.a[i] * inv;
      c.j_scaled[i] = j[i] * inv;
    }
    c.rhs_scaled = rows[k].rhs * inv;
    f[k] = ClampStart(f[k]);
    for (std::size_t i = 0; i < 3; ++i) {
      u[i] += f[k] * c.a[i];
      u[i + 3] += f[k] * c.g[i];
    }
  }
  return u;
}

// One sweep of eq. 3.6 over all rows; returns the largest change of an f_k. Since
// (C f)_k = a_k·Δr + j_k·Δθ, row k's update is f_k + (rhs_k − a_k·Δr − j_k·Δθ)/c_kk, computed
// with a and j pre-divided by c_kk so the serial chain through (Δr, Δθ) is as short as it gets.
double ProxySolver::Sweep(std::span<double> f, std::array<double, 6>* state) noexcept {
  double d0 = (*state)[0], d1 = (*state)[1], d2 = (*state)[2];
  double t0 = (*state)[3], t1 = (*state)[4], t2 = (*state)[5];
  double max_change = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    const RowCache& c = cache_[k];
    const double scaled =
        ((c.a_scaled[0] * d0 + c.a_scaled[1] * d1) + (c.a_scaled[2] * d2 + c.j_scaled[0] * t0)) +
        (c.j_scaled[1] * t1 + c.j_scaled[2] * t2);
    const double next = std::max(0.0, (f[k] + c.rhs_scaled) - scaled);
    const double change = next - f[k];
    f[k] = next;
    d0 += change * c.a[0];
    d1 += change * c.a[1];
    d2 += change * c.a[2];
    t0 += change * c.g[0];
    t1 += change * c.g[1];
    t2 += change * c.g[2];
    max_change = std::max(max_change, std::abs(change));
  }
  *state = {d0, d1, d2, t0, t1, t2};
  return max_change;
}

Eigen::MatrixXd ProxyMatrix(std::span<const ProxyRow> rows, const Mat3& rotation_weight_inverse) {
  const auto m = static_cast<Eigen::Index>(rows.size());
  Eigen::Matrix3Xd a(3, m);
  Eigen::Matrix3Xd j(3, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    a.col(k) = rows[static_cast<std::size_t>(k)].a;
    j.col(k) = rows[static_cast<std::size_t>(k)].r.cross(a.col(k));
  }
  // eq. 3.5: c_kl = j_kᵀ R_w⁻¹ j_l + a_kᵀ a_l, i.e. C = Jᵀ R_w⁻¹ J + Aᵀ A.
  const Eigen::Matrix3Xd g = rotation_weight_inverse * j;
  return j.transpose() * g + a.transpose() * a;
}

ProxySolveResult SolveProxyDense(std::span<const ProxyRow> rows,
                                 const Mat3& rotation_weight_inverse,
                                 const ProxySolverSettings& settings, std::span<double> f) {
  const Eigen::MatrixXd c = ProxyMatrix(rows, rotation_weight_inverse);
  const std::size_t m = rows.size();
  for (std::size_t k = 0; k < m; ++k) f[k] = ClampStart(f[k]);
  ProxySolveResult result;
  if (m == 0) result.converged = true;
  for (int sweep = 0; m > 0 && sweep < settings.max_iterations; ++sweep) {
    double max_change = 0.0;
    // eq. 3.6: rows before i already hold sweep k+1 values, rows after i sweep k values.
    for (std::size_t i = 0; i < m; ++i) {
      const auto ii = static_cast<Eigen::Index>(i);
      double sum = rows[i].rhs;
      for (std::size_t j = 0; j < m; ++j) {
        if (j != i) sum -= c(ii, static_cast<Eigen::Index>(j)) * f[j];
      }
      const double next = std::max(0.0, sum / c(ii, ii));
      max_change = std::max(max_change, std::abs(next - f[i]));
      f[i] = next;
    }
    result.iterations = sweep + 1;
    result.max_change = max_change;
    if (max_change <= settings.tolerance) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace mrh::render
