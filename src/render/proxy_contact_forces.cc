// SPDX-License-Identifier: Apache-2.0
// 6-DOF proxy, contact torque model: the wrench the user feels and the objects' reactions as
// one set of contact forces.
#include <algorithm>
#include <cmath>

#include "mrh/render/proxy_renderer.h"

namespace mrh::render {

// With R_w = (k_r / k_t)·I the proxy's stationarity conditions read Δr = Σ f_k a_k and
// (k_r / k_t) Δθ = Σ f_k r_k × a_k, so the forces k_t f_k a_k at the rows' points carry exactly
// the spring wrench (k_t Δr, k_r Δθ) of eq. 3.7–3.8. A pair whose geom has a haptic material
// uses its stiffness k_i, damping d_i and μ_i in place of k_t, d_t and μ: its forces are
// k_i f_k a_k, so a pointer resting on it with offset δ feels k_i δ (the proxy's geometry does
// not depend on the gains; only the wrench is then no longer k_t Δr). Per pair i (normal n_i):
//  - normal load N_i = n_i · Σ_normal k_t f_k a_k; friction force F_t,i = Σ_friction k_t f_k a_k,
//    scaled by s_i = min(1, μ N_i / |F_t,i|) into the pair's Coulomb cone (the LCP bounds each
//    friction row's offset by μ δ, not its multiplier by μ f_n);
//  - the damper d_t of eq. 3.7 acts on the total load N = Σ_i N_i: every force of pair i is
//    scaled by max(0, 1 + (d_i / k_i) (N − N_prev) / (dt N)), which keeps centres of pressure and
//    cones and never pulls. Not on each pair's own load: where rows are redundant (a face on
//    several coplanar objects) the split of N among the pairs is not unique and the active set
//    may move load between pairs from one tick to the next with N unchanged; a per-pair rate
//    turned that into a felt force jumping by half its size every tick. On the first tick after
//    a start or reset the damper is at rest;
//  - if a pair's force exceeds max_pair_force, every pair's force is scaled by one factor so
//    the largest equals it (nearly contradictory rows: a proxy wedged between overlapping
//    objects); cones, centres of pressure and action = reaction are kept.
// The rendered wrench is the sum over all pairs (static ones included); each moving object
// receives minus its pairs' forces where they act, so action = reaction holds about every point.
void ProxyRenderer::ComputeContactForces(const TickIr& ir, const Pose& X_WP, double dt,
                                         ProxyOutput* out) noexcept {
  AddRowForces();
  double total_load = 0.0;
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    normal_load_[i] = std::max(0.0, ir.pairs[i].n_W.dot(force_pair_[i]));
    total_load += normal_load_[i];
  }
  const double rate = has_previous_ ? (total_load - previous_total_load_) / dt : 0.0;
  double largest = 0.0;
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    dr_pair_[i].setZero();
    dtheta_pair_[i].setZero();
    const double load = normal_load_[i];
    if (!(load > 0.0)) {
      force_pair_[i].setZero();
      torque_pair_[i].setZero();
      continue;
    }
    const double tau_d = gains_[i].damping / gains_[i].stiffness;  // s; k_i > 0 as load > 0
    const double friction = friction_force_[i].norm();
    const double limit = gains_[i].friction * load;
    const double cone = friction > limit ? limit / friction : 1.0;
    const double scale = std::max(0.0, 1.0 + tau_d * rate / total_load);
    force_pair_[i] = scale * (force_pair_[i] + cone * friction_force_[i]);
    torque_pair_[i] = scale * (torque_pair_[i] + cone * friction_torque_[i]);
    largest = std::max(largest, force_pair_[i].norm());
  }
  out->w_W = LimitedTotal(ir, largest, out);
  PushReactions(ir, X_WP, out);
}

// Every pair's force scaled by one factor so that the largest (`largest`) is at most
// max_pair_force (flagged in out's status); returns their sum.
Wrench ProxyRenderer::LimitedTotal(const TickIr& ir, double largest, ProxyOutput* out) noexcept {
  const double limit =
      largest > settings_.max_pair_force ? settings_.max_pair_force / largest : 1.0;
  if (limit < 1.0) out->diagnostics.status |= kProxyStatusPairForceLimited;
  Wrench total;
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    force_pair_[i] *= limit;
    torque_pair_[i] *= limit;
    total.f += force_pair_[i];
    total.tau += torque_pair_[i];
  }
  return total;
}

// Each row's spring force k_i f_k a_k (k_i the pair's stiffness: k_t without a material) and its
// moment about the pointer origin, summed per pair: normal rows into force_pair_/torque_pair_,
// friction rows into friction_force_/_torque_.
void ProxyRenderer::AddRowForces() noexcept {
  for (std::size_t i = 0; i < ir::kMaxGeometricPairs; ++i) {
    force_pair_[i].setZero();
    torque_pair_[i].setZero();
    friction_force_[i].setZero();
    friction_torque_[i].setZero();
  }
  const auto add = [&](std::size_t k) noexcept {
    const auto i = static_cast<std::size_t>(info_[k].pair);
    const Vec3 force = (gains_[i].stiffness * f_[k]) * rows_[k].a;
    const Vec3 moment = rows_[k].r.cross(force);
    if (info_[k].kind == ProxyRowKind::kNormal) {
      force_pair_[i] += force;
      torque_pair_[i] += moment;
    } else {
      friction_force_[i] += force;
      friction_torque_[i] += moment;
    }
  };
  if (settings_.solver == ProxySolverKind::kActiveSet) {
    for (const int k : active_set_.active_rows()) {
      if (f_[static_cast<std::size_t>(k)] != 0.0) add(static_cast<std::size_t>(k));
    }
  } else {
    for (std::size_t k = 0; k < row_count_; ++k) {
      if (f_[k] != 0.0) add(k);
    }
  }
}

}  // namespace mrh::render
