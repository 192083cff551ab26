// SPDX-License-Identifier: Apache-2.0
// Haptic half of B1 and B4: 3-DOF penalty rendering with the reaction sent as an impulse.
#include "point_penalty_haptic.h"

#include <algorithm>

#include "mrh/render/point_penalty.h"
#include "normal_carry.h"

namespace mrh::haptic::internal {

void PointPenaltyHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  // Carry each pair's last rendered normal as the start of its blend (SPEC §3.9); a new pair
  // starts at its new normal.
  CarryRenderedNormals(snapshot, snapshot_, rendered_n_, &previous_n_);
  snapshot_ = snapshot;
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) rendered_n_[i] = previous_n_[i];
}

void PointPenaltyHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const double alpha = std::min(1.0, static_cast<double>(in.j + 1) / static_cast<double>(in.n));
  out->w_W = Wrench{};
  out->contacts = 0;
  for (std::size_t b = 0; b < snapshot_.bodies.size(); ++b) {
    tick_force_[b].setZero();
    tick_torque_[b].setZero();
  }
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) {
    const ir::PointContact& c = snapshot_.contacts[i];
    const auto motion = static_cast<std::size_t>(c.motion);
    const ir::BodyMotion& body = snapshot_.bodies[motion];
    const Pose X_WB = Interpolate(body.X_WB_prev, body.X_WB, alpha);
    Vec3 n = (1.0 - alpha) * previous_n_[i] + alpha * c.n_W;
    n.normalize();
    rendered_n_[i] = n;
    render::PlaneContactState s;
    s.p_WO = X_WB * c.p_BC;
    s.n_W = n;
    const Vec3 p_WCm = X_WB * body.p_BCm;
    s.v_WO = body.V_WCm.v + body.V_WCm.w.cross(s.p_WO - p_WCm);
    s.p_WC = in.X_WP.p - radius_ * n;
    s.v_WC = in.V_WP.v + in.V_WP.w.cross(s.p_WC - in.X_WP.p);
    const render::PointPenaltyResult r = render::RenderPointPenalty(s, stiffness_, damping_);
    if (r.magnitude <= 0.0) continue;
    ++out->contacts;
    out->w_W.f += r.f_W;
    out->w_W.tau += (s.p_WC - in.X_WP.p).cross(r.f_W);
    if (!body.is_static) {
      // eq. 4.12: the object receives −f_d at the plane point.
      tick_force_[motion] -= r.f_W;
      tick_torque_[motion] += (s.p_WO - p_WCm).cross(-r.f_W);
    }
  }
  for (ir::BodyImpulse& entry : period_.impulses) entry.last_force = Vec3::Zero();
  for (std::size_t b = 0; b < snapshot_.bodies.size(); ++b) {
    if (tick_force_[b].isZero(0.0) && tick_torque_[b].isZero(0.0)) continue;
    period_.AddImpulse(snapshot_.bodies[b].body, tick_force_[b] * in.dt, tick_torque_[b] * in.dt,
                       tick_force_[b]);
  }
}

void PointPenaltyHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  report->status |= period_.status;
  period_.impulses.Clear();
  period_.status = ir::kStatusOk;
}

}  // namespace mrh::haptic::internal
