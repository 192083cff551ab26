// SPDX-License-Identifier: Apache-2.0
// Haptic half of B1 and B4: 3-DOF penalty rendering with the reaction sent as an impulse.
#include "point_penalty_haptic.h"

#include <algorithm>

#include "mrh/render/point_penalty.h"
#include "normal_carry.h"

namespace mrh::haptic::internal {

void PointPenaltyHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  // Carry each pair's last rendered normal as the start of its blend (thesis §4.3.1); a new pair
  // starts at its new normal.
  CarryRenderedNormals(snapshot, snapshot_, rendered_n_, &previous_n_);
  snapshot_ = snapshot;
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) rendered_n_[i] = previous_n_[i];
}

// Contact i's penalty force (corrected eq. 4.11) into out and its reaction into this tick's
// per-body sums.
void PointPenaltyHaptic::RenderContact(std::size_t i, const TickInput& in, double alpha,
                                       TickOutput* out) noexcept {
  const ir::PointContact& c = snapshot_.contacts[i];
  // The geom's material, or rendering.* (3-DOF contacts have no friction).
  const ir::ContactGains g = ir::GainsOf(c.material, {stiffness_, damping_, friction_});
  const auto motion = static_cast<std::size_t>(c.motion);
  const ir::BodyMotion& body = snapshot_.bodies[motion];
  const Vec3 n = render::BlendNormal(previous_n_[i], c.n_W, alpha);
  rendered_n_[i] = n;
  const render::BlendedPoint o = render::BlendBodyPoint(body, c.p_BC, alpha);
  const render::SphereContact contact = render::TouchSpherePlane(
      o.p_WO, o.v_WO, n, in.X_WP.p, in.V_WP, radius_, g.stiffness, g.damping);
  if (contact.result.magnitude <= 0.0) return;
  ++out->contacts;
  transients_.Touch(c.geom, contact.state.n_W, render::ApproachSpeed(contact),
                    c.material.vibration);
  Wrench w = render::PointerWrench(contact, in.X_WP.p);
  Vec3 f_W = contact.result.f_W;
  if (friction_ > 0.0 && g.friction > 0.0) {
    const Pose X_WB = Interpolate(body.X_WB_prev, body.X_WB, alpha);
    const Vec3 f_t = anchors_.Friction(c.geom, X_WB, contact.state.p_WC, contact.state.n_W,
                                       g.stiffness, g.friction, contact.result.magnitude);
    f_W += f_t;
    w.f += f_t;
    w.tau += (contact.state.p_WC - in.X_WP.p).cross(f_t);
  }
  out->w_W.f += w.f;
  out->w_W.tau += w.tau;
  if (!body.is_static) {
    // eq. 4.12: the object receives −f_d at the plane point.
    tick_force_[motion] -= f_W;
    tick_torque_[motion] += (o.p_WO - o.p_WCm).cross(-f_W);
  }
}

void PointPenaltyHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const double alpha = in.alpha();
  out->w_W = Wrench{};
  out->contacts = 0;
  for (std::size_t b = 0; b < snapshot_.bodies.size(); ++b) {
    tick_force_[b].setZero();
    tick_torque_[b].setZero();
  }
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) RenderContact(i, in, alpha, out);
  if (friction_ > 0.0) anchors_.ReleaseUntouched();
  render::AddTransientForce(in.dt, &transients_, &out->w_W.f);
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
