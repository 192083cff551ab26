// SPDX-License-Identifier: Apache-2.0
// local-dynamics, physics half, step (0): local → global synchronization (eq. 4.16–4.17) and the
// group extension.
#include "local_dynamics_physics.h"
#include "mrh/core/spatial.h"
#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {

// (0) eq. 4.16–4.17. The report's period rendered the snapshot before the latest one, so only
// its bodies are written: the physics side's merged report may still hold states of bodies
// that left the neighborhood earlier (they have been simulated globally since).
void LocalDynamicsPhysics::Overwrite(const ir::HapticReport& report) {
  sync_failed_.clear();
  for (const ir::LocalBodyState& state : report.local_states) {
    const SentBody* sent = FindSent(sent_before_, state.body);
    if (sent == nullptr) continue;
    const world::BodyState global = world_->body_state(state.body);
    // Plus the correction the period now rendering added at its first tick (see the class
    // comment): the global step must start where that period did.
    ir::LocalBodyState corrected = state;
    const SentBody* next = FindSent(sent_last_, state.body);
    if (next != nullptr) {
      corrected.V_WCm.v += next->dV_sent.v;
      corrected.V_WCm.w += next->dV_sent.w;
    }
    if (world_->SetBodyState(state.body, corrected.X_WB, corrected.V_WCm)) {
      ++counters_.overwrites;
      SyncGroup(*sent, global, corrected);
      continue;
    }
    // The joints cannot take the local state (e.g. a link of a moving chain): deliver the
    // period's reaction as the impulse method does, and restart the local simulation.
    ++counters_.overwrite_failures;
    sync_failed_.push_back(state.body);
    ApplyReportImpulses(*world_, report, physics_dt_, state.body);
  }
}

// The extension described at LocalDynamicsMethod: Δ_j = A_jB A_B⁺ Δ for the neighbor's group.
void LocalDynamicsPhysics::SyncGroup(const SentBody& sent, const world::BodyState& global,
                                     const ir::LocalBodyState& local) {
  if (sent.members == 0) return;
  // Columns: the twist discrepancy and the pose discrepancy (COM shift, rotation vector).
  Eigen::Matrix<double, 6, 2> delta;
  delta.col(0) << local.V_WCm.v - global.V_WCm.v, local.V_WCm.w - global.V_WCm.w;
  delta.col(1) << local.X_WB * world_->body(sent.body).p_BCm - global.p_WCm,
      RotationVectorFromQuat(local.X_WB.q.normalized() * global.X_WB.q.conjugate());
  // The force-like amounts that explain the discrepancy through the neighbor's own response
  // (least squares: A_B is 6×3 and may be rank-deficient, e.g. with slide joints).
  const Eigen::Matrix<double, 3, 2> phi = sent.A.completeOrthogonalDecomposition().solve(delta);
  for (std::size_t i = sent.first_member; i < sent.first_member + sent.members; ++i) {
    const world::GroupResponse& member = group_before_[i];
    // A body simulated locally itself is synchronized from its own state (each neighbor's A maps
    // only the force on itself; neighbors are not cross-coupled).
    if (FindSent(sent_before_, member.body) != nullptr) continue;
    const Eigen::Matrix<double, 6, 2> delta_j = member.A * phi;
    const world::BodyState state = world_->body_state(member.body);
    const Vec3 rotation = delta_j.col(1).tail<3>();
    const Quat q = (QuatFromRotationVector(rotation) * state.X_WB.q).normalized();
    const Vec3 p_WCm = state.p_WCm + delta_j.col(1).head<3>();
    const Pose X_WB{p_WCm - q * world_->body(member.body).p_BCm, q};
    const Twist V{state.V_WCm.v + delta_j.col(0).head<3>(),
                  state.V_WCm.w + delta_j.col(0).tail<3>()};
    if (world_->SetBodyState(member.body, X_WB, V)) {
      ++counters_.group_syncs;
    } else {
      ++counters_.group_sync_failures;
    }
  }
}

}  // namespace mrh::physics::internal
