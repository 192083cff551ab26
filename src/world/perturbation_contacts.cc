// SPDX-License-Identifier: Apache-2.0
// The Perturber's contact queries: the contacts of the zero-force run, and the velocity change
// that contacts outside a known set gave a body in the step just taken.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <vector>

#include "mrh/core/assert.h"
#include "mrh/world/perturbation.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

using internal::ToVec3;

// The body's own degrees of freedom (a free joint has 6).
constexpr int kMaxOwnDofs = 6;
using OwnVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxOwnDofs, 1>;
using OwnMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxOwnDofs, kMaxOwnDofs>;

// M_B: the own block (dofs first .. first + count − 1) of the joint-space mass matrix (a body's
// dofs form one chain; a row of MuJoCo's sparse lower-triangular M lists the dof's ancestors in
// increasing order).
OwnMatrix OwnMass(const mjModel& m, const mjData& d, int first, int count) {
  OwnMatrix M(count, count);
  M.setZero();
  for (int i = 0; i < count; ++i) {
    const int row = first + i;
    for (int k = m.M_rowadr[row]; k < m.M_rowadr[row] + m.M_rownnz[row]; ++k) {
      const int j = m.M_colind[k];
      if (j >= first) M(i, j - first) = M(j - first, i) = d.M[k];
    }
  }
  return M;
}

// Adds J_Bᵀ (f; τ) of contact `i` to `out`, over the body's own dofs. MuJoCo's contact frame has
// its normal from geom1 to geom2, and the force acts on geom2 (sign +1; −1 for geom1).
void AddContactForce(const mjModel& m, const mjData& d, int i, int body, double sign,
                     std::vector<double>* jacp, std::vector<double>* jacr, OwnVector* out) {
  const mjContact& c = d.contact[i];
  std::array<mjtNum, 6> local{};
  mj_contactForce(&m, &d, i, local.data());
  Vec3 f_W = Vec3::Zero();
  Vec3 tau_W = Vec3::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    const Vec3 direction = ToVec3(c.frame + 3 * axis);
    f_W += sign * local[static_cast<std::size_t>(axis)] * direction;
    tau_W += sign * local[static_cast<std::size_t>(3 + axis)] * direction;
  }
  mj_jac(&m, &d, jacp->data(), jacr->data(), c.pos, body);
  const int first = m.body_dofadr[body];
  for (int k = 0; k < out->size(); ++k) {
    for (int r = 0; r < 3; ++r) {
      const auto column = static_cast<std::size_t>(r * m.nv + first + k);
      (*out)[k] += (*jacp)[column] * f_W[r] + (*jacr)[column] * tau_W[r];
    }
  }
}

}  // namespace

std::uint64_t ContactKey(int geom_a, int geom_b) {
  const auto lo = static_cast<std::uint32_t>(std::min(geom_a, geom_b));
  const auto hi = static_cast<std::uint32_t>(std::max(geom_a, geom_b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

void Perturber::RecordBaseContacts() {
  const mjData& d = *world_->impl_->data;
  base_contacts_.clear();
  for (int i = 0; i < d.ncon; ++i) {
    base_contacts_.push_back(ContactKey(d.contact[i].geom1, d.contact[i].geom2));
  }
  std::sort(base_contacts_.begin(), base_contacts_.end());
}

std::span<const std::uint64_t> Perturber::base_contacts() const {
  MRH_DEMAND(zero_done_);
  return base_contacts_;
}

// The contacts and constraint forces in the data are those of the step's forward pass (at the
// state the step started from), as are the kinematics and the mass matrix until a query
// refreshes them: exactly what the integrator used.
Twist Perturber::NewContactVelocityChange(int body, std::span<const std::uint64_t> known) {
  const World::Impl& w = *world_->impl_;
  const mjModel& m = *w.model;
  const mjData& d = *w.data;
  MRH_DEMAND(body >= 0 && body < m.nbody);
  const int first = m.body_dofadr[body];
  const int count = m.body_dofnum[body];
  if (count <= 0 || count > kMaxOwnDofs) return Twist{};
  OwnVector generalized = OwnVector::Zero(count);
  bool any = false;
  for (int i = 0; i < d.ncon; ++i) {
    const mjContact& c = d.contact[i];
    const int body1 = m.geom_bodyid[c.geom1];
    const int body2 = m.geom_bodyid[c.geom2];
    if ((body1 == body) == (body2 == body) || c.efc_address < 0) continue;
    if (std::binary_search(known.begin(), known.end(), ContactKey(c.geom1, c.geom2))) continue;
    AddContactForce(m, d, i, body, body2 == body ? 1.0 : -1.0, &jacp_, &jacr_, &generalized);
    any = true;
  }
  if (!any) return Twist{};
  const OwnMatrix M = OwnMass(m, d, first, count);
  const auto dq = (M.llt().solve(generalized) * m.opt.timestep).eval();
  mj_jacBodyCom(&m, &d, jacp_.data(), jacr_.data(), body);
  Twist dV;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < count; ++k) {
      dV.v[r] += jacp_[static_cast<std::size_t>(r * m.nv + first + k)] * dq[k];
      dV.w[r] += jacr_[static_cast<std::size_t>(r * m.nv + first + k)] * dq[k];
    }
  }
  return dV;
}

}  // namespace mrh::world
