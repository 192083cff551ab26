// SPDX-License-Identifier: Apache-2.0
// 6-DOF proxy: how the rendered wrench is split between several touched objects.
#include <algorithm>
#include <cmath>

#include "mrh/render/proxy_renderer.h"

namespace mrh::render {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

constexpr int kMaxNewtonSteps = 12;
// The penalty weight of the dual (relative to trace H): 1e-8 of the points' stiffness.
constexpr double kRidge = 1e-8;

}  // namespace

// Several touched pairs (SPEC §3.6 with I5, made physical). Where the pointer presses several
// objects, the solver's multipliers f_k split the load in one of many ways (1000 coplanar
// points over 8 boxes: the active set loads two corners), and the proxy's torque k_r Δθ is not
// the moment of its rows' forces (those are offsets in the R_w metric). Either way, giving each
// object its rows' share makes forces act far from where that object is touched: a light box
// far from the pointer origin then takes the couple of a lever glued to it, tilts into the
// pointer, presses harder and diverges (issue 14, the 1000-contact benchmark).
//
// So the rendered wrench (F, τ about the pointer origin) is matched by forces λ_k a_k >= 0 at
// the penetrating points themselves, spread as a compliant contact would spread them:
// minimize Σ λ_k² / δ_k subject to Σ λ_k a_k = F, Σ λ_k r_k × a_k = τ, λ_k >= 0 (δ_k the
// point's depth; a linear pressure on a flat patch). The dual is a 6-vector y with
// λ_k = δ_k max(0, w_k·y), w_k = [a_k; r_k × a_k / L]: a convex piecewise quadratic, solved by
// Newton with backtracking. Whatever of (F, τ) the points cannot carry (a torque outside the
// patches' reach) goes to the pairs in proportion to their force. Σ over the pairs is (F, τ)
// exactly, so action = reaction holds in force and moment.
void ProxyRenderer::SplitAcrossPairs(const TickIr& ir, std::size_t touched,
                                     const ProxyOutput* out) noexcept {
  double length2 = 0.0;
  for (std::size_t k = 0; k < row_count_; ++k) length2 += rows_[k].r.squaredNorm();
  const double length = std::max(1e-3, std::sqrt(length2 / static_cast<double>(row_count_)));
  const auto w_of = [&](std::size_t k) noexcept {
    Vec6 w;
    w.head<3>() = rows_[k].a;
    w.tail<3>() = rows_[k].r.cross(rows_[k].a) / length;
    return w;
  };
  const auto depth_of = [&](std::size_t k) noexcept {
    return std::max(ir.points[static_cast<std::size_t>(info_[k].point)].depth, 1e-9);
  };
  Vec6 target;
  target.head<3>() = out->w_W.f;
  target.tail<3>() = out->w_W.tau / length;
  Mat6 h = Mat6::Zero();
  for (std::size_t k = 0; k < row_count_; ++k) {
    h.selfadjointView<Eigen::Lower>().rankUpdate(w_of(k), depth_of(k));
  }
  // A small penalty |Σ λ_k w_k − W|² in place of the hard constraint keeps the dual strongly
  // convex where W has parts no point can carry (a sideways force on a frictionless face): y
  // then stays bounded along them and they go to the leftover.
  const double ridge = kRidge * std::max(h.trace(), 1e-300);
  // φ(y) = ½ Σ δ_k max(0, w_k·y)² + ½ ridge |y|² − W·y, its gradient and Hessian.
  const auto evaluate = [&](const Vec6& y, Vec6* g, Mat6* hessian) noexcept {
    double phi = 0.5 * ridge * y.squaredNorm() - target.dot(y);
    if (g != nullptr) *g = ridge * y - target;
    if (hessian != nullptr) *hessian = ridge * Mat6::Identity();
    for (std::size_t k = 0; k < row_count_; ++k) {
      const Vec6 w = w_of(k);
      const double s = w.dot(y);
      if (!(s > 0.0)) continue;
      const double d = depth_of(k);
      phi += 0.5 * d * s * s;
      if (g != nullptr) *g += (d * s) * w;
      if (hessian != nullptr) hessian->selfadjointView<Eigen::Lower>().rankUpdate(w, d);
    }
    if (hessian != nullptr) *hessian = hessian->selfadjointView<Eigen::Lower>();
    return phi;
  };
  Vec6 y = (h + ridge * Mat6::Identity()).ldlt().solve(target);
  Vec6 g;
  double phi = evaluate(y, &g, &h);
  for (int step = 0; step < kMaxNewtonSteps && g.norm() > 1e-12 * target.norm(); ++step) {
    const Vec6 dy = h.ldlt().solve(g);
    double t = 1.0;
    double next = evaluate(y - dy, nullptr, nullptr);
    for (int halving = 0; halving < 30 && next > phi - 1e-4 * t * g.dot(dy); ++halving) {
      t *= 0.5;
      next = evaluate(y - t * dy, nullptr, nullptr);
    }
    y -= t * dy;
    phi = evaluate(y, &g, &h);
  }
  // Each pair's forces at its points: F_i and its moment M_i about the pointer origin.
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    force_pair_[i].setZero();
    torque_pair_[i].setZero();
  }
  for (std::size_t k = 0; k < row_count_; ++k) {
    const double s = w_of(k).dot(y);
    if (!(s > 0.0)) continue;
    const Vec3 f = (depth_of(k) * s) * rows_[k].a;
    const auto i = static_cast<std::size_t>(info_[k].pair);
    force_pair_[i] += f;
    torque_pair_[i] += rows_[k].r.cross(f);
  }
  Vec3 left_f = out->w_W.f, left_tau = out->w_W.tau;
  double load = 0.0;
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    left_f -= force_pair_[i];
    left_tau -= torque_pair_[i];
    load += force_pair_[i].norm();
  }
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    const double share =
        load > 0.0 ? force_pair_[i].norm() / load
                   : (pair_rows_[i] > 0 ? 1.0 / static_cast<double>(touched) : 0.0);
    force_pair_[i] += share * left_f;
    torque_pair_[i] += share * left_tau;
  }
}

}  // namespace mrh::render
