// SPDX-License-Identifier: Apache-2.0
// Random proxy LCPs with a known feasible displacement, shared by the proxy solver tests.
#pragma once

#include <cmath>
#include <random>
#include <vector>

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

}  // namespace mrh::render::testing
