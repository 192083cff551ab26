// SPDX-License-Identifier: Apache-2.0
// Rows on the joint-space trees' coordinates: a contact's generalized Jacobian and response,
// and the coordinates' dry friction and limits as MuJoCo's soft rows.
#include <algorithm>
#include <cmath>
#include <limits>

#include "mrh/render/local_contact_solver.h"
#include "soft_constraint.h"

namespace mrh::render {
namespace {

constexpr std::size_t kS = LocalContactSolver::kMaxTreeDofs;
constexpr int kDofPasses = 10;

}  // namespace

double LocalContactSolver::TreeVelocity(const std::array<double, kMaxTreeDofs>& g) const noexcept {
  double v = 0.0;
  for (std::size_t k = 0; k < dof_count_; ++k) v += g[k] * qd_[k];
  return v;
}

void LocalContactSolver::ApplyTree(const std::array<double, kMaxTreeDofs>& h, double dl) noexcept {
  for (std::size_t k = 0; k < dof_count_; ++k) qd_[k] += dl * h[k];
}

// The generalized Jacobian of row r's directions over the coordinates of the tree sides, their
// response h = M⁻¹ g, and their share of A_jj (r.inv_w) and of the tangents' coupling (r.a12).
void LocalContactSolver::SetTreeRow(Row& r) noexcept {
  r.tree = static_cast<int>(tree_rows_count_++);
  TreeRow& t = tree_rows_[static_cast<std::size_t>(r.tree)];
  const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
  for (std::size_t j = 0; j < 3; ++j) {
    std::array<double, kMaxTreeDofs>& g = t.g[j];
    std::fill(g.begin(), g.begin() + static_cast<std::ptrdiff_t>(dof_count_), 0.0);
    if (r.a_tree) AddTreeJacobian(A, A.p + r.rA, r.d[j], 1.0, g.data());
    if (r.b_tree) {
      const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
      AddTreeJacobian(B, B.p + r.rB, r.d[j], -1.0, g.data());
    }
    for (std::size_t k = 0; k < dof_count_; ++k) {
      double h = 0.0;
      for (std::size_t l = 0; l < dof_count_; ++l) h += Minv_[k * kS + l] * g[l];
      t.h[j][k] = h;
    }
    for (std::size_t k = 0; k < dof_count_; ++k) r.inv_w[j] += g[k] * t.h[j][k];
  }
  for (std::size_t k = 0; k < dof_count_; ++k) r.a12 += t.g[1][k] * t.h[2][k];
}

// A row on coordinate `dof` with velocity sign·q̇; A_jj in inv_w until its R is known.
LocalContactSolver::DofRow& LocalContactSolver::AddDofRow(std::size_t dof, int slot,
                                                          double sign) noexcept {
  DofRow& r = dof_rows_[dof_rows_count_++];
  r = DofRow{};
  r.dof = static_cast<int>(dof);
  r.slot = slot;
  r.sign = sign;
  r.inv_w = Minv_[dof * kS + dof];
  r.lo = -std::numeric_limits<double>::infinity();
  r.hi = std::numeric_limits<double>::infinity();
  return r;
}

// Each coordinate's dry friction (MuJoCo's soft friction-loss row, its impulse within
// ±frictionloss Δt) and its range's two ends (hard and speculative inside range − margin,
// MuJoCo's soft limit beyond), as the row joints take them; warm-started.
void LocalContactSolver::PrepareDofRows(double dt) noexcept {
  dof_rows_count_ = 0;
  for (std::size_t k = 0; k < dof_count_; ++k) {
    const ir::LocalJoint& j = joints_[static_cast<std::size_t>(dofs_[k].joint)];
    const int base = dofs_[k].joint * static_cast<int>(kJointSlots);
    const double diag = j.inv_weight > 0.0 ? j.inv_weight : Minv_[k * kS + k];
    if (j.frictionloss > 0.0) {
      DofRow& r = AddDofRow(k, base + kFrictionSlot, 1.0);
      const internal::SoftRow s =
          internal::FrictionLossRow(j.solref_friction, j.solimp_friction, dt, qd0_[k], diag);
      r.target = s.target;
      r.R = s.R;
      r.lo = -j.frictionloss * dt;
      r.hi = j.frictionloss * dt;
    }
    for (int side = 0; j.limited && side < 2; ++side) {
      const double sign = side == 0 ? 1.0 : -1.0;
      const double gap = sign * (q_[k] - j.range[side]) - j.margin;
      DofRow& r = AddDofRow(k, base + kLimitSlot + side, sign);
      const internal::SoftRow s =
          internal::LimitRow(j.solref_limit, j.solimp_limit, dt, gap, sign * qd0_[k], diag);
      r.target = s.target;
      r.R = s.R;
      r.lo = 0.0;
    }
  }
  for (std::size_t i = 0; i < dof_rows_count_; ++i) {
    DofRow& r = dof_rows_[i];
    r.inv_w = r.inv_w + r.R > 0.0 ? 1.0 / (r.inv_w + r.R) : 0.0;
    const double l = joint_lambda_[static_cast<std::size_t>(r.slot)];
    if (l != 0.0) ApplyDof(r, l);
  }
}

void LocalContactSolver::ApplyDof(const DofRow& r, double dl) noexcept {
  const auto c = static_cast<std::size_t>(r.dof);
  for (std::size_t k = 0; k < dof_count_; ++k) qd_[k] += dl * r.sign * Minv_[k * kS + c];
}

// The trees' coordinate rows as one block of the sweep: passes over them (in the sweep's
// direction) until none changes by more than the tolerance, at most kDofPasses. Through M⁻¹
// every coordinate of a chain couples to every other, and the dry friction of a pushed chain's
// joints otherwise converges by a few per cent per sweep, holding the whole island at its sweep
// cap; the block costs O(rows · dofs) a pass. Returns the first pass's largest change.
double LocalContactSolver::SolveDofRows(bool forward) noexcept {
  double first = 0.0;
  for (int pass = 0; pass < kDofPasses; ++pass) {
    double change = 0.0;
    for (std::size_t i = 0; i < dof_rows_count_; ++i) {
      change = std::max(change, SolveDofRow(dof_rows_[forward ? i : dof_rows_count_ - 1 - i]));
    }
    if (pass == 0) first = change;
    if (change <= settings_.tolerance) break;
  }
  return first;
}

// One Gauss–Seidel update of a coordinate's row; returns its velocity change (rad/s or m/s).
double LocalContactSolver::SolveDofRow(DofRow& r) noexcept {
  double& l = joint_lambda_[static_cast<std::size_t>(r.slot)];
  const double next = internal::RowUpdate(l, r.sign * qd_[static_cast<std::size_t>(r.dof)],
                                          r.target, r.R, r.inv_w, r.lo, r.hi);
  const double dl = next - l;
  ApplyDof(r, dl);
  l = next;
  return internal::RowChange(dl, r.inv_w);
}

}  // namespace mrh::render
