// SPDX-License-Identifier: Apache-2.0
// Exact constraint solve of a test-force run on the pushed body's constraint island (private).
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

namespace mrh::world::internal {

/// MuJoCo's primal constraint problem (the one its CG and Newton solvers minimize,
///   min_a ½ (a − a_smooth)ᵀ M (a − a_smooth) + Σ_r s_r(J_r a − aref_r),
/// s_r = ½ D_r x² for an equality row, and for a contact or limit row while x < 0), restricted
/// to the dofs of one constraint island: the bodies linked to the pushed one by constraint rows
/// (and kinematic trees). A test force changes the solution only there, so a test-force run is
/// the small problem of that island instead of the whole world's. Solved exactly by active-set
/// iterations: with the active rows fixed the problem is quadratic, so the solution holds when
/// the active set it implies is the one assumed. Physics thread; buffers grow to the largest
/// island seen (capped by max_dofs); not RT-safe.
class IslandSolve {
 public:
  /// Finds the island of `body` in the forward pass held in `d` (constraint rows, mass matrix,
  /// kinematics at the saved state) and solves it without test force; `qacc_smooth` and `qacc`
  /// (nv each) are that forward pass's (they may have been overwritten in `d` by test-force
  /// runs since, which leave the rest unchanged). Returns false where the
  /// island cannot be solved here: more than `max_dofs` dofs, a row whose cost is not one of
  /// the quadratic pieces above (friction loss, elliptic cones), or no settled active set.
  bool Prepare(const mjModel& m, mjData* d, int body, int max_dofs, const double* qacc_smooth,
               const double* qacc);

  /// Writes qacc with force f_W (N, world) at p_W (m, world) on the prepared body into `qacc`:
  /// `qacc_zero` (all nv) plus the change the force makes on the island, i.e. the difference of
  /// the two exact island solutions. Returns false if the active set did not settle.
  /// @pre Prepare() returned true.
  bool Solve(const mjModel& m, mjData* d, const double f_W[3], const double p_W[3],
             const double* qacc_zero, double* qacc);

  /// Dofs of the prepared island; active-set iterations of the last Prepare() or Solve().
  int num_dofs() const { return static_cast<int>(dofs_.size()); }

  int iterations() const { return iterations_; }

  /// H⁻¹ Q with H = M + J_Aᵀ D_A J_A of the active set the last Prepare() settled on (valid
  /// until the next Solve()): the island's acceleration change per generalized force, one
  /// column of `qfrc` (island dofs, in dofs() order) each, while that active set holds.
  Eigen::MatrixXd SolveSettled(const Eigen::MatrixXd& qfrc) const { return llt_.solve(qfrc); }

  /// Island dofs (global indices, ascending) and the active rows of the last settled solve.
  const std::vector<int>& dofs() const { return dofs_; }

  int active_rows() const { return active_rows_; }

 private:
  bool CollectIsland(const mjModel& m, const mjData& d, int body, int max_dofs);
  void UniteLinkedBodies(const mjModel& m, const mjData& d);
  bool CollectRows(const mjModel& m, const mjData& d);
  bool SolveActiveSet(const Eigen::VectorXd& qfrc, Eigen::VectorXd* qacc);

  int Find(int body);

  std::vector<int> parent_;        // union-find over bodies
  std::vector<int> dofs_;          // island dofs (global indices), ascending
  std::vector<int> local_of_dof_;  // global dof → island index, −1 outside
  std::vector<int> rows_;          // island rows
  std::vector<bool> one_sided_;    // per island row: contact/limit (else equality)
  Eigen::MatrixXd J_;              // island rows × island dofs
  Eigen::VectorXd D_, aref_;       // per island row
  Eigen::MatrixXd M_;              // island block of the mass matrix
  Eigen::VectorXd M_a_smooth_;     // M_II a_smooth_I
  Eigen::VectorXd zero_;           // exact island solution without test force
  Eigen::MatrixXd H_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  std::vector<double> qfrc_;  // nv scratch for mj_applyFT
  int body_ = -1;
  int iterations_ = 0;
  int active_rows_ = 0;
};

}  // namespace mrh::world::internal
