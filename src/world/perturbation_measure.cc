// SPDX-License-Identifier: Apache-2.0
// A perturbation measurement: the three test forces, the accelerance A and bias b of the
// measured body from their runs, and the group of other bodies the forces moved.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "mrh/core/assert.h"
#include "mrh/world/perturbation.h"
#include "world/island_solve_impl.h"
#include "world/perturbation_kinematics.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

using internal::IsFreeBody;
using internal::IsSlideBody;
using internal::TwistAfterEuler;

// A body belongs to the measured body's group when the test forces change its velocity by more
// than this fraction of the measured body's change (far above solver noise, ~1e-12 relative).
constexpr double kGroupTolerance = 1e-6;

// e2 starts from x̂ unless x̂ is this close to e1 (|x̂·e1| above it), then from ŷ: keeps
// |x̂ − (x̂·e1)e1| >= sqrt(1 − 0.9²) ≈ 0.44, far from cancellation.
constexpr double kParallelDot = 0.9;

Vec6 ToVec6(const Twist& t) {
  Vec6 out;
  out << t.v, t.w;
  return out;
}

}  // namespace

Mat3 TestForces(const Vec3& f1) {
  const double magnitude = f1.norm();
  MRH_DEMAND(std::isfinite(magnitude) && magnitude > 0.0);
  const Vec3 e1 = f1 / magnitude;
  const Vec3 seed = std::abs(e1.x()) > kParallelDot ? Vec3::UnitY() : Vec3::UnitX();
  const Vec3 e2 = (seed - seed.dot(e1) * e1).normalized();
  const Vec3 e3 = e1.cross(e2);
  Mat3 F;
  F.col(0) = f1;
  F.col(1) = magnitude * (e1 + e2).normalized();  // eq. 4.5
  F.col(2) = magnitude * (e1 + e3).normalized();  // eq. 4.6, corrected (printed as eq. 4.5)
  return F;
}

DynamicIr Perturber::Measure(std::size_t index, const Vec3& f1, const Vec3& p_W) {
  MRH_DEMAND(open_ && zero_done_ && index < bodies_.size());
  const Mat3 F = TestForces(f1);
  const Vec6 u0 = ToVec6(zero_[index]);
  island_ready_ = false;
  if (forward_skip_ && settings_.island_solve) {
    const World::Impl& w = *world_->impl_;
    island_ready_ =
        island_->Prepare(*w.model, w.data.get(), bodies_[index], settings_.max_island_dofs,
                         zero_smooth_.data(), zero_q_.data());
    counters_.island_iterations += island_->iterations();
    if (island_ready_) {
      counters_.max_island_dofs = std::max(counters_.max_island_dofs, island_->num_dofs());
    } else {
      ++counters_.island_fallbacks;
    }
  }
  Mat63 Y;
  for (int k = 0; k < 3; ++k) {
    // eq. 4.8 (corrected: rearranging eq. 4.3 gives −b, not +b): y_k = (u_k − u_0)/Δt; b cancels.
    Y.col(k) = (ToVec6(Run(index, F.col(k), p_W, k)) - u0) / dt_;
  }
  island_ready_ = false;
  const Mat3 F_inverse = F.inverse();
  DynamicIr ir;
  ir.A = Y * F_inverse;                       // eq. 4.10
  ir.b = (u0 - ToVec6(start_[index])) / dt_;  // eq. 4.3 with f = 0
  CollectGroup(bodies_[index], F_inverse);
  return ir;
}

// Bodies other than `measured` whose generalized velocities the three runs changed by more than
// kGroupTolerance of the measured body's change, with their accelerances for the same forces.
void Perturber::CollectGroup(int measured, const Mat3& F_inverse) {
  const World::Impl& w = *world_->impl_;
  const mjModel& m = *w.model;
  const mjData& d = *w.data;
  // Velocity change of dof i in run k: (qacc_k − qacc_0)·Δt when skipping, else qvel_k − qvel_0.
  const double scale = forward_skip_ ? dt_ : 1.0;
  auto response = [&](int body) {
    double largest = 0.0;
    for (const std::vector<double>& run : run_q_) {
      for (int i = m.body_dofadr[body]; i < m.body_dofadr[body] + m.body_dofnum[body]; ++i) {
        const auto dof = static_cast<std::size_t>(i);
        largest = std::max(largest, std::abs(run[dof] - zero_q_[dof]) * scale);
      }
    }
    return largest;
  };
  group_.clear();
  const double threshold = kGroupTolerance * response(measured);
  for (int body = 1; body < m.nbody; ++body) {
    if (body == measured || m.body_dofnum[body] == 0 || !(response(body) > threshold)) continue;
    if (forward_skip_ && !IsFreeBody(m, body) && !IsSlideBody(m, body)) {
      ++counters_.group_bodies_unread;
      continue;
    }
    const auto b = static_cast<std::size_t>(body);
    const Vec6 u0 =
        ToVec6(forward_skip_ ? TwistAfterEuler(m, d, body, dt_, zero_q_.data()) : zero_twists_[b]);
    Mat63 Y;
    for (std::size_t k = 0; k < 3; ++k) {
      const Twist u =
          forward_skip_ ? TwistAfterEuler(m, d, body, dt_, run_q_[k].data()) : run_twists_[k][b];
      Y.col(static_cast<int>(k)) = (ToVec6(u) - u0) / dt_;
    }
    group_.push_back(GroupResponse{body, Y * F_inverse});
  }
}

}  // namespace mrh::world
