// SPDX-License-Identifier: Apache-2.0
// Exact constraint solve of a test-force run on the pushed body's constraint island.
#include <algorithm>
#include <numeric>

#include "world/island_solve_impl.h"

namespace mrh::world::internal {
namespace {

// Active-set iterations before giving up (the caller then runs MuJoCo's solver). A push changes
// the activity of a few rows at most; each iteration settles at least the rows it flips.
constexpr int kMaxActiveSetIterations = 16;

// Calls f(column, value) for every non-zero of constraint row r, dense or sparse Jacobian.
template <typename F>
void ForEachNonzero(const mjModel& m, const mjData& d, int r, F f) {
  if (mj_isSparse(&m)) {
    const int adr = d.efc_J_rowadr[r];
    for (int k = 0; k < d.efc_J_rownnz[r]; ++k) f(d.efc_J_colind[adr + k], d.efc_J[adr + k]);
    return;
  }
  for (int c = 0; c < m.nv; ++c) {
    const mjtNum v = d.efc_J[static_cast<std::ptrdiff_t>(r) * m.nv + c];
    if (v != 0.0) f(c, v);
  }
}

// Rows whose cost is ½ D x² while x = J a − aref < 0 (false: always, equality); other types
// (friction loss: linear beyond a band; elliptic cones) are not handled here.
bool RowKind(int type, bool* one_sided) {
  switch (type) {
    case mjCNSTR_EQUALITY:
      *one_sided = false;
      return true;
    case mjCNSTR_LIMIT_JOINT:
    case mjCNSTR_LIMIT_TENDON:
    case mjCNSTR_CONTACT_FRICTIONLESS:
    case mjCNSTR_CONTACT_PYRAMIDAL:
      *one_sided = true;
      return true;
    default:
      return false;
  }
}

}  // namespace

int IslandSolve::Find(int body) {
  while (parent_[static_cast<std::size_t>(body)] != body) {
    int& p = parent_[static_cast<std::size_t>(body)];
    p = parent_[static_cast<std::size_t>(p)];  // path halving
    body = p;
  }
  return body;
}

// Bodies are linked by every constraint row between their dofs and by their kinematic trees
// (which couple dofs through M): union–find over the bodies.
void IslandSolve::UniteLinkedBodies(const mjModel& m, const mjData& d) {
  parent_.resize(static_cast<std::size_t>(m.nbody));
  std::iota(parent_.begin(), parent_.end(), 0);
  auto unite = [this](int a, int b) {
    parent_[static_cast<std::size_t>(Find(a))] = Find(b);
  };
  for (int i = 0; i < m.nv; ++i) {
    if (m.dof_parentid[i] >= 0) unite(m.dof_bodyid[i], m.dof_bodyid[m.dof_parentid[i]]);
  }
  for (int r = 0; r < d.nefc; ++r) {
    int first = -1;
    ForEachNonzero(m, d, r, [&](int c, mjtNum) {
      const int b = m.dof_bodyid[c];
      if (first < 0)
        first = b;
      else
        unite(first, b);
    });
  }
}

// The rows that touch a dof of the island; false on a row kind the solve does not handle.
bool IslandSolve::CollectRows(const mjModel& m, const mjData& d) {
  rows_.clear();
  one_sided_.clear();
  for (int r = 0; r < d.nefc; ++r) {
    bool in_island = false;
    ForEachNonzero(m, d, r, [&](int c, mjtNum) {
      in_island = in_island || local_of_dof_[static_cast<std::size_t>(c)] >= 0;
    });
    if (!in_island) continue;
    bool one_sided = false;
    if (!RowKind(d.efc_type[r], &one_sided)) return false;
    rows_.push_back(r);
    one_sided_.push_back(one_sided);
  }
  return true;
}

// The island is the component of `body`: its dofs (at most max_dofs) and rows.
bool IslandSolve::CollectIsland(const mjModel& m, const mjData& d, int body, int max_dofs) {
  UniteLinkedBodies(m, d);
  const int root = Find(body);
  dofs_.clear();
  local_of_dof_.assign(static_cast<std::size_t>(m.nv), -1);
  for (int i = 0; i < m.nv; ++i) {
    if (Find(m.dof_bodyid[i]) != root) continue;
    if (static_cast<int>(dofs_.size()) == max_dofs) return false;
    local_of_dof_[static_cast<std::size_t>(i)] = static_cast<int>(dofs_.size());
    dofs_.push_back(i);
  }
  return CollectRows(m, d) && !dofs_.empty();
}

bool IslandSolve::Prepare(const mjModel& m, mjData* d, int body, int max_dofs,
                          const double* qacc_smooth, const double* qacc) {
  iterations_ = 0;
  body_ = body;
  if (!CollectIsland(m, *d, body, max_dofs)) return false;
  const auto n = static_cast<Eigen::Index>(dofs_.size());
  const auto rows = static_cast<Eigen::Index>(rows_.size());
  J_.setZero(rows, n);
  D_.resize(rows);
  aref_.resize(rows);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const int r = rows_[static_cast<std::size_t>(k)];
    ForEachNonzero(m, *d, r, [&](int c, mjtNum v) {
      J_(k, local_of_dof_[static_cast<std::size_t>(c)]) = v;
    });
    D_[k] = d->efc_D[r];
    aref_[k] = d->efc_aref[r];
  }
  // The island block of M: each dof's row of MuJoCo's sparse M (lower triangle, CSR) holds the
  // dof and its chain of parent dofs, all in the island.
  M_.setZero(n, n);
  Eigen::VectorXd a_smooth(n), guess(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int g = dofs_[static_cast<std::size_t>(i)];
    const int first = m.M_rowadr[g];
    for (int k = first; k < first + m.M_rownnz[g]; ++k) {
      const int lj = local_of_dof_[static_cast<std::size_t>(m.M_colind[k])];
      M_(i, lj) = M_(lj, i) = d->M[k];
    }
    a_smooth[i] = qacc_smooth[g];
    guess[i] = qacc[g];  // MuJoCo's own solution: the active set is nearly right
  }
  M_a_smooth_ = M_ * a_smooth;
  zero_ = guess;
  return SolveActiveSet(Eigen::VectorXd::Zero(n), &zero_);
}

bool IslandSolve::Solve(const mjModel& m, mjData* d, const double f_W[3], const double p_W[3],
                        const double* qacc_zero, double* qacc) {
  qfrc_.assign(static_cast<std::size_t>(m.nv), 0.0);
  const mjtNum no_torque[3] = {0.0, 0.0, 0.0};
  mj_applyFT(&m, d, f_W, no_torque, p_W, body_, qfrc_.data());
  const auto n = static_cast<Eigen::Index>(dofs_.size());
  Eigen::VectorXd qfrc(n);
  for (Eigen::Index i = 0; i < n; ++i) qfrc[i] = qfrc_[static_cast<std::size_t>(dofs_[i])];
  Eigen::VectorXd solution = zero_;
  if (!SolveActiveSet(qfrc, &solution)) return false;
  std::copy_n(qacc_zero, m.nv, qacc);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int g = dofs_[static_cast<std::size_t>(i)];
    qacc[g] = qacc_zero[g] + (solution[i] - zero_[i]);
  }
  return true;
}

// With the active rows A fixed, the optimality condition is linear:
// (M + J_Aᵀ D_A J_A) a = M a_smooth + qfrc + J_Aᵀ D_A aref_A. Iterate until the solution makes
// exactly the assumed rows active (then it is the minimizer: the cost is convex and C¹).
bool IslandSolve::SolveActiveSet(const Eigen::VectorXd& qfrc, Eigen::VectorXd* qacc) {
  const auto rows = J_.rows();
  Eigen::VectorXd weight(rows);
  Eigen::VectorXd previous = Eigen::VectorXd::Constant(rows, -1.0);
  for (iterations_ = 0; iterations_ < kMaxActiveSetIterations; ++iterations_) {
    const Eigen::VectorXd x = J_ * *qacc - aref_;
    for (Eigen::Index k = 0; k < rows; ++k) {
      weight[k] = !one_sided_[static_cast<std::size_t>(k)] || x[k] < 0.0 ? D_[k] : 0.0;
    }
    if (iterations_ > 0 && weight == previous) {
      active_rows_ = static_cast<int>((weight.array() != 0.0).count());
      return true;
    }
    previous = weight;
    H_ = M_;
    H_.noalias() += J_.transpose() * weight.asDiagonal() * J_;
    llt_.compute(H_);
    if (llt_.info() != Eigen::Success) return false;
    *qacc = llt_.solve(M_a_smooth_ + qfrc + J_.transpose() * weight.cwiseProduct(aref_));
  }
  return false;
}

}  // namespace mrh::world::internal
