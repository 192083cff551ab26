// SPDX-License-Identifier: Apache-2.0
// 6-DOF proxy: how the rendered wrench is split between several touched objects.
#include <algorithm>
#include <array>
#include <cmath>

#include "mrh/render/proxy_renderer.h"

namespace mrh::render {
namespace {

// Newton steps of the split (PressureSplit); warm-started, a sustained contact takes 1–2.
constexpr int kMaxNewtonSteps = 20;

}  // namespace

// Several touched pairs (the reaction on the objects, which the thesis only says is computed on
// the haptic side, §3.5, made physical). Where the pointer presses several
// objects, the solver's multipliers f_k split the load in one of many ways (1000 coplanar
// points over 8 boxes: the active set loads two corners), and the proxy's torque k_r Δθ is not
// the moment of its rows' forces (those are offsets in the R_w metric). Either way, giving each
// object its rows' share makes forces act far from where that object is touched: a light box
// far from the pointer origin then takes the couple of a lever glued to it, tilts into the
// pointer, presses harder and diverges (as in the 1000-contact benchmark).
//
// So the rendered wrench (F, τ about the pointer origin) is matched by forces λ_k a_k >= 0 at
// the penetrating points themselves, spread as a compliant contact would spread them:
// minimize Σ λ_k² / δ_k subject to Σ λ_k a_k = F, Σ λ_k r_k × a_k = τ, λ_k >= 0 (δ_k the
// point's depth; a linear pressure on a flat patch), solved by PressureSplit (a piecewise Newton
// method on its 6-vector dual, warm-started from the last tick). Whatever of (F, τ) the points
// cannot carry (a torque outside the patches' reach) goes to the pairs in proportion to their
// force. Σ over the pairs is (F, τ) exactly, so action = reaction holds in force and moment.
void ProxyRenderer::SplitAcrossPairs(const TickIr& ir, std::size_t touched,
                                     const ProxyOutput* out) noexcept {
  PairPlanes plane;
  LoadSplit(ir, &plane);
  (void)split_.Solve(out->w_W.f, out->w_W.tau, kMaxNewtonSteps);
  CollectPairWrenches(ir, plane);
  SpreadRemainder(ir, touched, out);
}

// The split's rows, one per penetrating point; *plane gets each pair's tangent plane (or -1).
void ProxyRenderer::LoadSplit(const TickIr& ir, PairPlanes* plane) noexcept {
  // Normal rows push (λ >= 0). A point with a friction row may take a tangential force either
  // way in its pair's plane (its cone is the solver's business, not the split's): a two-sided
  // tangent plane per pair in place of a one-sided row along the slip, whose clipping otherwise
  // flips with the rubbing direction and leaves the split many Newton steps.
  PairPlanes group{};
  plane->fill(-1);
  group.fill(-1);
  split_.Begin();
  for (std::size_t k = 0; k < row_count_; ++k) {
    const double depth = ir.points[static_cast<std::size_t>(info_[k].point)].depth;
    const auto i = static_cast<std::size_t>(info_[k].pair);
    if (info_[k].kind == ProxyRowKind::kNormal) {  // a pair's normal rows share its normal
      split_row_[split_.size()] = static_cast<int>(k);
      if (group[i] < 0) group[i] = split_.AddGroup(rows_[k].a);
      if (group[i] < 0 || rows_[k].a != split_.group_direction(group[i]) ||
          !split_.AddGroupRow(group[i], rows_[k].r, depth)) {
        (void)split_.AddRow(rows_[k].a, rows_[k].r, depth);
      }
      continue;
    }
    if ((*plane)[i] < 0) (*plane)[i] = split_.AddPlane(ir.pairs[i].n_W);
    split_.AddTangentPoint((*plane)[i], rows_[k].r, depth);
  }
}

// Each pair's forces at its points after the split's solve: F_i and its moment M_i about the
// pointer origin.
void ProxyRenderer::CollectPairWrenches(const TickIr& ir, const PairPlanes& plane) noexcept {
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    split_.PlaneWrench(plane[i], &force_pair_[i], &torque_pair_[i]);
  }
  for (std::size_t j = 0; j < split_.size(); ++j) {
    const double lambda = split_.lambda(j);
    if (lambda == 0.0) continue;
    const auto k = static_cast<std::size_t>(split_row_[j]);
    const Vec3 f = lambda * split_.direction(j);
    const auto i = static_cast<std::size_t>(info_[k].pair);
    force_pair_[i] += f;
    torque_pair_[i] += rows_[k].r.cross(f);
  }
}

// What the points could not carry goes to the pairs in proportion to their force (evenly over
// the touched pairs when none carries any).
void ProxyRenderer::SpreadRemainder(const TickIr& ir, std::size_t touched,
                                    const ProxyOutput* out) noexcept {
  Vec3 left_f = out->w_W.f, left_tau = out->w_W.tau;
  double load = 0.0;
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    left_f -= force_pair_[i];
    left_tau -= torque_pair_[i];
    load += force_pair_[i].norm();
  }
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    const double share = load > 0.0
                             ? force_pair_[i].norm() / load
                             : (pair_rows_[i] > 0 ? 1.0 / static_cast<double>(touched) : 0.0);
    force_pair_[i] += share * left_f;
    torque_pair_[i] += share * left_tau;
  }
}

}  // namespace mrh::render
