// SPDX-License-Identifier: Apache-2.0
// local-dynamics, contact local model, haptic half: the island at 1 kHz and 3-DOF penalty
// rendering against planes fixed on its bodies.
#include <algorithm>

#include "local_contact_haptic.h"
#include "mrh/render/point_penalty.h"

namespace mrh::haptic::internal {

LocalContactHaptic::LocalContactHaptic(double radius, double stiffness, double damping,
                                       const render::LocalContactSolverSettings& solver)
    : radius_(radius), stiffness_(stiffness), damping_(damping), solver_(solver) {
  local_of_motion_.fill(-1);
}

// Island bodies that stay in the island keep their local state (LocalContactSolver::Adopt); a
// plane on an island body keeps its normal in the body frame, so it turns with the local body.
void LocalContactHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  CarryRenderedNormals(snapshot, snapshot_, rendered_n_, &previous_n_);
  snapshot_ = snapshot;
  solver_.Adopt(snapshot_.local_model);
  for (std::size_t m = 0; m < snapshot_.bodies.size(); ++m) {
    local_of_motion_[m] = solver_.FindMotion(static_cast<int>(m));
  }
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) {
    const ir::PointContact& c = snapshot_.contacts[i];
    n_B_[i] = snapshot_.bodies[static_cast<std::size_t>(c.motion)].X_WB.q.conjugate() * c.n_W;
    rendered_n_[i] = previous_n_[i];
  }
}

void LocalContactHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const double alpha = std::min(1.0, static_cast<double>(in.j + 1) / static_cast<double>(in.n));
  out->w_W = Wrench{};
  out->contacts = 0;
  out->status = 0;
  for (ir::BodyImpulse& entry : period_.impulses) entry.last_force = Vec3::Zero();
  RenderContacts(in, alpha, out);
  if (!solver_.Step(in.dt)) {
    ++counters_.local_faults;
    out->status |= kLocalBodyFault;
  }
  ++counters_.ticks;
}

// Corrected eq. 4.11 against every contact's plane; the reaction (eq. 4.12) goes to the island
// body in this tick, or, for a body outside the island, into the period's impulse.
void LocalContactHaptic::RenderContacts(const TickInput& in, double alpha,
                                        TickOutput* out) noexcept {
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) {
    const ir::PointContact& c = snapshot_.contacts[i];
    const auto motion = static_cast<std::size_t>(c.motion);
    const ir::BodyMotion& body = snapshot_.bodies[motion];
    const int local = local_of_motion_[motion];
    render::PlaneContactState s;
    Vec3 p_WCm;
    if (local >= 0) {
      const auto l = static_cast<std::size_t>(local);
      const Pose X_WB = solver_.X_WB(l);
      s.n_W = X_WB.q * n_B_[i];
      s.p_WO = X_WB * c.p_BC;
      s.v_WO = solver_.PointVelocity(l, s.p_WO);
      p_WCm = solver_.p_WCm(l);
    } else {
      s.n_W = ((1.0 - alpha) * previous_n_[i] + alpha * c.n_W).normalized();
      const Pose X_WB = Interpolate(body.X_WB_prev, body.X_WB, alpha);
      p_WCm = X_WB * body.p_BCm;
      s.p_WO = X_WB * c.p_BC;
      s.v_WO = body.V_WCm.v + body.V_WCm.w.cross(s.p_WO - p_WCm);
    }
    rendered_n_[i] = s.n_W;
    s.p_WC = in.X_WP.p - radius_ * s.n_W;
    s.v_WC = in.V_WP.v + in.V_WP.w.cross(s.p_WC - in.X_WP.p);
    const render::PointPenaltyResult r = render::RenderPointPenalty(s, stiffness_, damping_);
    if (r.magnitude <= 0.0) continue;
    ++out->contacts;
    out->w_W.f += r.f_W;
    out->w_W.tau += (s.p_WC - in.X_WP.p).cross(r.f_W);
    if (body.is_static) continue;
    if (local >= 0) solver_.AddForce(static_cast<std::size_t>(local), -r.f_W, s.p_WO);
    period_.AddImpulse(body.body, -r.f_W * in.dt, (s.p_WO - p_WCm).cross(-r.f_W) * in.dt,
                       -r.f_W);
  }
}

void LocalContactHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  report->local_states.Clear();
  for (std::size_t i = 0; i < solver_.size(); ++i) {
    if (!report->local_states.PushBack(
            ir::LocalBodyState{solver_.world_body(i), solver_.X_WB(i), solver_.V_WCm(i)})) {
      period_.status |= ir::kStatusBodiesFull;
    }
  }
  report->status |= period_.status;
  period_.impulses.Clear();
  period_.status = ir::kStatusOk;
}

}  // namespace mrh::haptic::internal
