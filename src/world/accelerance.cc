// SPDX-License-Identifier: Apache-2.0
// 6×6 accelerance estimates of T4.6 (accelerance.h): perturbation runs over whole steps, the
// analytic island estimate and the converged reference.
#include "mrh/world/accelerance.h"

#include <mujoco/mujoco.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <array>
#include <chrono>
#include <cmath>
#include <vector>

#include "mrh/core/assert.h"
#include "mrh/world/perturbation.h"
#include "world/island_solve_impl.h"
#include "world/perturbation_kinematics.h"
#include "world/world_impl.h"

namespace mrh::world {

// The MuJoCo model and data behind a World (World's friend).
class AcceleranceAccess {
 public:
  static internal::WorldState& Of(World* world) { return *world->impl_; }
};

namespace {

std::int64_t NowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

Vec6 ToVec6(const Twist& t) {
  Vec6 out;
  out << t.v, t.w;
  return out;
}

Wrench ToWrench(const Vec6& w) {
  return Wrench{w.head<3>(), w.tail<3>()};
}

Mat3 Skew(const Vec3& r) {
  Mat3 s;
  s << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return s;
}

// Whole-step runs from a saved state: each adds its wrench on the body, steps once, reads the
// body's COM twist and restores. Counts the steps.
class StepRuns {
 public:
  StepRuns(World* world, int body) : world_(world), body_(body), snapshot_(world->MakeSnapshot()) {}

  ~StepRuns() { world_->Restore(snapshot_); }

  StepRuns(const StepRuns&) = delete;
  StepRuns& operator=(const StepRuns&) = delete;

  Vec6 Run(const Vec6& wrench) {
    if (wrench.squaredNorm() > 0.0) world_->AddWrenchAtCom(body_, ToWrench(wrench));
    world_->Step();
    ++steps_;
    // A free or slide body's COM twist straight from qpos and qvel: no whole-world kinematics.
    const auto& w = AcceleranceAccess::Of(world_);
    const bool direct =
        internal::IsFreeBody(*w.model, body_) || internal::IsSlideBody(*w.model, body_);
    const Vec6 u =
        ToVec6(direct ? internal::TwistAfterEuler(*w.model, *w.data, body_, 0.0, w.data->qacc)
                      : world_->body_state(body_).V_WCm);
    world_->Restore(snapshot_);
    return u;
  }

  int steps() const { return steps_; }

 private:
  World* world_;
  int body_;
  Snapshot snapshot_;
  int steps_ = 0;
};

// Newton with the settings' tolerance and iteration limit while alive; the model's own after.
class ConvergedSolver {
 public:
  ConvergedSolver(World* world, const ConvergedSettings& settings)
      : m_(AcceleranceAccess::Of(world).model.get()),
        solver_(m_->opt.solver),
        tolerance_(m_->opt.tolerance),
        iterations_(m_->opt.iterations) {
    m_->opt.solver = mjSOL_NEWTON;
    m_->opt.tolerance = settings.tolerance;
    m_->opt.iterations = settings.iterations;
  }

  ~ConvergedSolver() {
    m_->opt.solver = solver_;
    m_->opt.tolerance = tolerance_;
    m_->opt.iterations = iterations_;
  }

  ConvergedSolver(const ConvergedSolver&) = delete;
  ConvergedSolver& operator=(const ConvergedSolver&) = delete;

 private:
  mjModel* m_;
  int solver_;
  mjtNum tolerance_;
  int iterations_;
};

// The 18 wrenches of the full estimate as columns: each test force with ±torque about x, y, z.
Eigen::Matrix<double, 6, 18> FullWrenches(const Vec3& f_user, double torque) {
  const Mat3 F = TestForces(f_user);
  Eigen::Matrix<double, 6, 18> W;
  int k = 0;
  for (int i = 0; i < 3; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      for (const double sign : {1.0, -1.0}) {
        W.col(k) << F.col(i), sign * torque * Vec3::Unit(axis);
        ++k;
      }
    }
  }
  return W;
}

// The body's COM Jacobian (rows [v; ω], world) restricted to the island's dofs.
Eigen::MatrixXd IslandComJacobian(const mjModel& m, mjData* d, int body,
                                  const std::vector<int>& dofs) {
  std::vector<mjtNum> jacp(3 * static_cast<std::size_t>(m.nv)), jacr(jacp.size());
  mj_jacBodyCom(&m, d, jacp.data(), jacr.data(), body);
  Eigen::MatrixXd J(6, static_cast<Eigen::Index>(dofs.size()));
  for (Eigen::Index c = 0; c < J.cols(); ++c) {
    const auto dof = static_cast<std::size_t>(dofs[static_cast<std::size_t>(c)]);
    const auto nv = static_cast<std::size_t>(m.nv);
    for (std::size_t r = 0; r < 3; ++r) {
      J(static_cast<Eigen::Index>(r), c) = jacp[r * nv + dof];
      J(static_cast<Eigen::Index>(r + 3), c) = jacr[r * nv + dof];
    }
  }
  return J;
}

}  // namespace

Mat66 FreeBodyInverseMass(const World& world, int body) {
  const BodyInfo& info = world.body(body);
  MRH_DEMAND(info.mass > 0.0);
  const Mat3 R = world.body_state(body).X_WB.q.toRotationMatrix();
  const Mat3 I_W = R * info.inertia_B * R.transpose();
  Mat66 A = Mat66::Zero();
  A.topLeftCorner<3, 3>() = Mat3::Identity() / info.mass;
  A.bottomRightCorner<3, 3>() = I_W.inverse();
  return A;
}

AcceleranceEstimate MeasureConvergedAccelerance(World* world, int body, const Wrench& applied,
                                                const ConvergedSettings& settings) {
  const std::int64_t t0 = NowNs();
  const ConvergedSolver solver(world, settings);
  StepRuns runs(world, body);
  Vec6 base;
  base << applied.f, applied.tau;
  AcceleranceEstimate out;
  const double dt = world->timestep();
  for (int k = 0; k < 6; ++k) {
    const double eps = k < 3 ? settings.epsilon_force : settings.epsilon_torque;
    const Vec6 e = eps * Vec6::Unit(k);
    out.A.col(k) = (runs.Run(base + e) - runs.Run(base - e)) / (2.0 * eps * dt);
  }
  out.ok = out.A.allFinite();
  out.cost.steps = runs.steps();
  out.cost.wall_ns = NowNs() - t0;
  return out;
}

AcceleranceEstimate EstimateFull18(World* world, int body, const Vec3& f_user, double torque) {
  MRH_DEMAND(torque > 0.0);
  const std::int64_t t0 = NowNs();
  const Eigen::Matrix<double, 6, 18> W = FullWrenches(f_user, torque);
  StepRuns runs(world, body);
  const double dt = world->timestep();
  const Vec6 u0 = runs.Run(Vec6::Zero());
  Eigen::Matrix<double, 6, 18> Y;
  for (int k = 0; k < 18; ++k) Y.col(k) = (runs.Run(W.col(k)) - u0) / dt;
  AcceleranceEstimate out;
  // Least squares: A = Y Wᵀ (W Wᵀ)⁻¹ (W Wᵀ = blockdiag(6 F Fᵀ, 6 τ² I₃): the ± torques cancel).
  const Mat66 WWt = W * W.transpose();
  out.A = WWt.ldlt().solve(W * Y.transpose()).transpose();
  out.ok = out.A.allFinite();
  out.cost.steps = runs.steps();
  out.cost.wall_ns = NowNs() - t0;
  return out;
}

AcceleranceEstimate EstimateTwoRun(World* world, int body, const Wrench& user) {
  const std::int64_t t0 = NowNs();
  Vec6 w;
  w << user.f, user.tau;
  MRH_DEMAND(w.squaredNorm() > 0.0);
  const Mat66 A0 = FreeBodyInverseMass(*world, body);
  StepRuns runs(world, body);
  const double dt = world->timestep();
  const Vec6 u0 = runs.Run(Vec6::Zero());
  const Vec6 y = (runs.Run(w) - u0) / dt;
  const Vec6 d = A0 * w - y;
  const double denom = d.dot(w);
  AcceleranceEstimate out;
  out.A = A0;
  // |dᵀw| ≤ 1e-12 wᵀA₀w: the body moved as a free body (to rounding), keep the prior.
  if (std::abs(denom) > 1e-12 * w.dot(A0 * w)) out.A -= d * d.transpose() / denom;
  out.ok = out.A.allFinite();
  out.cost.steps = runs.steps();
  out.cost.wall_ns = NowNs() - t0;
  return out;
}

AcceleranceEstimate EstimateAnalytic(World* world, int body, const Wrench& applied,
                                     int max_island_dofs) {
  const std::int64_t t0 = NowNs();
  auto& w = AcceleranceAccess::Of(world);
  const mjModel& m = *w.model;
  mjData* d = w.data.get();
  const Snapshot saved = world->MakeSnapshot();
  world->AddWrenchAtCom(body, applied);
  AcceleranceEstimate out;
  {
    const std::int64_t f0 = NowNs();
    const internal::MujocoScope scope(w.origin);
    mj_forward(&m, d);
    out.cost.forward_ns = NowNs() - f0;
  }
  out.cost.forwards = 1;
  internal::IslandSolve island;
  if (island.Prepare(m, d, body, max_island_dofs, d->qacc_smooth, d->qacc)) {
    const Eigen::MatrixXd J = IslandComJacobian(m, d, body, island.dofs());
    out.A = J * island.SolveSettled(J.transpose());
    out.ok = out.A.allFinite();
    out.island_dofs = island.num_dofs();
    out.active_rows = island.active_rows();
  }
  world->Restore(saved);
  out.cost.wall_ns = NowNs() - t0;
  return out;
}

Mat3 PointAccelerance(const Mat66& A, const Vec3& r) {
  Eigen::Matrix<double, 6, 3> G;
  G << Mat3::Identity(), Skew(r);
  return G.transpose() * A * G;
}

double RelativeError(const Mat66& A, const Mat66& A_ref, double length) {
  Vec6 s;
  s << 1.0, 1.0, 1.0, length, length, length;
  const Mat66 S = s.asDiagonal();
  return (S * (A - A_ref) * S).norm() / (S * A_ref * S).norm();
}

}  // namespace mrh::world
