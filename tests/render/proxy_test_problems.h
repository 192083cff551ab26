// SPDX-License-Identifier: Apache-2.0
// Random proxy LCPs with a known feasible displacement, and one-call solves of them, shared by
// the proxy solver tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "mrh/render/proxy_active_set.h"
#include "mrh/render/proxy_solver.h"

namespace mrh::render::testing {

struct Problem {
  std::vector<ProxyRow> rows;
  Mat3 w_inv;
};

/// m rows built around a known displacement (Δr*, Δθ*), so the LCP has a solution: rhs_k is the
/// move row k asks of it minus a slack that is zero for about half the rows (active). R_w is a
/// random SPD matrix scaled by 10^(low + span·u), u uniform in [0, 1) (m²).
inline Problem RandomProblem(std::mt19937* rng, int m, double weight_decades_low = -2.0,
                             double weight_decades_span = 2.0) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Vec3 dr_star = 1e-3 * Vec3(normal(*rng), normal(*rng), normal(*rng));
  const Vec3 dtheta_star = 1e-2 * Vec3(normal(*rng), normal(*rng), normal(*rng));
  Mat3 a;
  for (int i = 0; i < 9; ++i) a(i / 3, i % 3) = normal(*rng);
  const double scale = std::pow(10.0, weight_decades_low + weight_decades_span * unit(*rng));
  const Mat3 weight = scale * (a * a.transpose() + 0.1 * Mat3::Identity());
  Problem p{{}, weight.inverse()};
  for (int k = 0; k < m; ++k) {
    ProxyRow row;
    row.a = Vec3(normal(*rng), normal(*rng), normal(*rng)).normalized();
    row.r = 0.1 * Vec3(normal(*rng), normal(*rng), normal(*rng));
    const double slack = unit(*rng) < 0.5 ? 0.0 : 1e-3 * unit(*rng);
    row.rhs = row.a.dot(dtheta_star.cross(row.r) + dr_star) - slack;
    p.rows.push_back(row);
  }
  return p;
}

/// What one Solve returned: the multipliers f, the displacement (Δr m, Δθ rad) and the result.
struct Solved {
  std::vector<double> f;
  Vec3 dr = Vec3::Zero();
  Vec3 dtheta = Vec3::Zero();
  ProxySolveResult result;
};

/// A regular n-gon face (radius 5 cm, 5 cm below the pointer origin) pressed 1 mm ± 20 % into a
/// floor z = 0, dragged 0.1 mm along −x and twisted 1 mrad about z: a normal row along z and a
/// friction row along the slip of each vertex (T3.4's shape, 2n rows).
inline std::vector<ProxyRow> PrismFaceRows(int n) {
  std::vector<ProxyRow> rows;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * 3.141592653589793 * i / n;
    const Vec3 r(0.05 * std::cos(angle), 0.05 * std::sin(angle), -0.05);
    const double depth = 1e-3 * (1.0 + 0.2 * std::cos(angle));
    rows.push_back(ProxyRow{Vec3::UnitZ(), r, depth});
    const Vec3 slip = Vec3(-1e-4, 0, 0) - 1e-3 * Vec3::UnitZ().cross(r);
    rows.push_back(ProxyRow{slip.normalized(), r, std::min(slip.norm(), 0.5 * depth)});
  }
  return rows;
}

/// Solves `rows` with a fresh `Solver` (ProxySolver or ProxyActiveSetSolver) from `start`, or
/// from zeros when `start` is empty.
template <typename Solver>
Solved SolveWith(const std::vector<ProxyRow>& rows, const Mat3& w_inv,
                 const ProxySolverSettings& settings, std::vector<double> start = {}) {
  Solved s;
  s.f = start.empty() ? std::vector<double>(rows.size(), 0.0) : start;
  Solver solver(rows.size() + 1);
  s.result = solver.Solve(rows, w_inv, settings, s.f, &s.dr, &s.dtheta);
  return s;
}

/// The O(m) PGS sweep (ProxySolver).
inline Solved SolveFast(const std::vector<ProxyRow>& rows, const Mat3& w_inv,
                        const ProxySolverSettings& settings, std::vector<double> start = {}) {
  return SolveWith<ProxySolver>(rows, w_inv, settings, std::move(start));
}

/// The exact active-set solver (ProxyActiveSetSolver), by default with 64 steps and 1e-14 m.
inline Solved SolveExact(const std::vector<ProxyRow>& rows, const Mat3& w_inv,
                         const ProxySolverSettings& settings = {64, 1e-14},
                         std::vector<double> start = {}) {
  return SolveWith<ProxyActiveSetSolver>(rows, w_inv, settings, std::move(start));
}

/// Expects the LCP conditions of eq. 3.4 at s.f for every row k: f_k >= 0, w_k >= −tol and
/// min(f_k, |w_k|) <= tol, with w = C f − rhs and tol in m. `trial` labels the failures.
inline void ExpectLcpConditions(const Problem& p, const Solved& s, double tol, int trial) {
  const Eigen::MatrixXd c = ProxyMatrix(p.rows, p.w_inv);
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    double w = -p.rows[k].rhs;
    for (std::size_t l = 0; l < p.rows.size(); ++l) {
      w += c(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) * s.f[l];
    }
    EXPECT_GE(s.f[k], 0.0) << "trial " << trial << " row " << k;
    EXPECT_GE(w, -tol) << "trial " << trial << " row " << k;
    EXPECT_LE(std::min(s.f[k], std::abs(w)), tol) << "trial " << trial << " row " << k;
  }
}

}  // namespace mrh::render::testing
