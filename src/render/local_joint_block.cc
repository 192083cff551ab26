// SPDX-License-Identifier: Apache-2.0
// The joints' bilateral rows of the contact local model (position rows; the coordinates'
// damping and armature, soft) solved as one block per sweep: their
// Delassus matrix J M⁻¹ Jᵀ factored once per tick (Cholesky), then each sweep applies the
// impulses that meet every position row at once given the other rows' current impulses.
#include <algorithm>
#include <cmath>

#include "mrh/render/local_contact_solver.h"

namespace mrh::render {

// The relative velocity of row ri per unit impulse on row rj (1/kg): the entry (i, j) of
// J M⁻¹ Jᵀ.
double LocalContactSolver::BlockCoupling(const JointRow& ri, const JointRow& rj) const noexcept {
  double c = 0.0;
  // Row j's unit impulse moves body x by sign (inv_mass d_j, m) (m = I⁻¹ j of row j's side).
  const auto add = [&](int x, double sign, const Vec3& m) {
    if (x < 0 || (x != ri.a && x != ri.b)) return;
    const Vec3 dv = (sign * bodies_[static_cast<std::size_t>(x)].inv_mass) * rj.d;
    const Vec3 dw = sign * m;
    if (x == ri.a) c += ri.d.dot(dv) + ri.jA.dot(dw);
    if (x == ri.b) c -= ri.d.dot(dv) + ri.jB.dot(dw);
  };
  add(rj.a, 1.0, rj.mA);
  add(rj.b, -1.0, rj.mB);
  return c;
}

// Collects this tick's position rows (up to kMaxBlockRows; the rest stay scalar) and factors
// their Delassus matrix. A matrix that is not positive definite (rows that depend on each
// other) leaves every row scalar for the tick.
void LocalContactSolver::PrepareJointBlock() noexcept {
  block_count_ = 0;
  for (std::size_t k = 0; k < jrows_count_; ++k) {
    JointRow& r = jrows_[k];
    if (!r.block) continue;
    if (block_count_ == kMaxBlockRows) {
      r.block = false;
      continue;
    }
    block_rows_[static_cast<std::size_t>(block_count_++)] = static_cast<int>(k);
  }
  if (block_count_ == 0) return;
  block_D_.resize(block_count_, block_count_);
  block_b_.resize(block_count_);
  for (int i = 0; i < block_count_; ++i) {
    const JointRow& ri = jrows_[static_cast<std::size_t>(block_rows_[static_cast<std::size_t>(i)])];
    for (int j = 0; j <= i; ++j) {
      const JointRow& rj =
          jrows_[static_cast<std::size_t>(block_rows_[static_cast<std::size_t>(j)])];
      block_D_(i, j) = block_D_(j, i) = BlockCoupling(ri, rj);
    }
    block_D_(i, i) += ri.R;
  }
  block_llt_.compute(block_D_);
  if (block_llt_.info() == Eigen::Success) return;
  for (int i = 0; i < block_count_; ++i) {
    jrows_[static_cast<std::size_t>(block_rows_[static_cast<std::size_t>(i)])].block = false;
  }
  block_count_ = 0;
}

// One exact solve of the block: Δλ = (D + R)⁻¹ (target − J v − R λ) applied to every row of the
// block (R = 0 for a position row). Returns the largest residual it removed (m/s or rad/s).
double LocalContactSolver::SolveJointBlock() noexcept {
  double change = 0.0;
  for (int i = 0; i < block_count_; ++i) {
    const JointRow& r = jrows_[static_cast<std::size_t>(block_rows_[static_cast<std::size_t>(i)])];
    block_b_[i] = r.target - JointRowVelocity(r, false) -
                  r.R * joint_lambda_[static_cast<std::size_t>(r.slot)];
    change = std::max(change, std::abs(block_b_[i]));
  }
  if (block_count_ == 0) return 0.0;
  block_llt_.solveInPlace(block_b_);
  for (int i = 0; i < block_count_; ++i) {
    JointRow& r = jrows_[static_cast<std::size_t>(block_rows_[static_cast<std::size_t>(i)])];
    ApplyJointImpulse(r, block_b_[i]);
    joint_lambda_[static_cast<std::size_t>(r.slot)] += block_b_[i];
  }
  return change;
}

// The joint rows outside the block (damping, armature, friction, limits, overflow), one
// Gauss–Seidel pass in the sweep's direction.
double LocalContactSolver::SolveScalarJointRows(bool forward) noexcept {
  double change = 0.0;
  for (std::size_t i = 0; i < jrows_count_; ++i) {
    JointRow& r = jrows_[forward ? i : jrows_count_ - 1 - i];
    if (!r.block) change = std::max(change, SolveJointRow(r));
  }
  return change;
}

}  // namespace mrh::render
