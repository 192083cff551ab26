// SPDX-License-Identifier: Apache-2.0
// Haptic half of local-dynamics: local simulation of the neighbors and 3-DOF penalty rendering.
#include "local_dynamics_haptic.h"

#include <algorithm>

#include "normal_carry.h"

namespace mrh::haptic::internal {

// A body that continues keeps its local state (the local simulation owns it while it stays a
// neighbor, thesis §4.2.1) and gets the correction of eq. 4.18 at its first tick; a new neighbor
// starts from the global state. Normals blend from the last rendered one (thesis §4.3.1, after
// Hasegawa et al. 1999).
void LocalDynamicsHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  CarryRenderedNormals(snapshot, snapshot_, rendered_n_, &previous_n_);
  const LocalBodies& old = local();
  LocalBodies& next = locals_[1 - current_];
  for (std::size_t i = 0; i < snapshot.bodies.size(); ++i) {
    const ir::BodyMotion& m = snapshot.bodies[i];
    pending_[i] = false;
    if (!m.has_dynamics) continue;
    bool carried = false;
    for (std::size_t o = 0; m.continues && o < snapshot_.bodies.size(); ++o) {
      if (snapshot_.bodies[o].body == m.body && snapshot_.bodies[o].has_dynamics) {
        next[i] = old[o];
        carried = true;
        break;
      }
    }
    if (!carried) next[i].Reset(m.X_WB, m.p_BCm, m.V_WCm);
    next[i].SetDynamics(m.A, m.b);
    pending_[i] = carried;
    pending_dV_[i] = m.dV_n;
  }
  current_ = 1 - current_;
  snapshot_ = snapshot;
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) rendered_n_[i] = previous_n_[i];
}

void LocalDynamicsHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const double alpha = in.alpha();
  out->w_W = Wrench{};
  out->contacts = 0;
  out->status = 0;
  for (std::size_t b = 0; b < snapshot_.bodies.size(); ++b) {
    tick_force_[b].setZero();
    tick_torque_[b].setZero();
    if (pending_[b]) {
      local()[b].AddVelocity(pending_dV_[b]);  // eq. 4.18, third term, once
      pending_[b] = false;
      ++haptic_counters_.corrections;
    }
  }
  RenderContacts(in, alpha, out);
  render::AddTransientForce(in.dt, &transients_, &out->w_W.f);
  StepLocalBodies(in, out);
  ++haptic_counters_.ticks;
}

// Corrected eq. 4.11 against every contact's plane: on a dynamic neighbor the plane moves with
// its local body; a static or kinematic body is blended between its step poses as in B4.
void LocalDynamicsHaptic::RenderContacts(const TickInput& in, double alpha,
                                         TickOutput* out) noexcept {
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) {
    const ir::PointContact& c = snapshot_.contacts[i];
    // The geom's material, or rendering.* (3-DOF contacts have no friction).
    const ir::ContactGains g = ir::GainsOf(c.material, {stiffness_, damping_, 0.0});
    const auto motion = static_cast<std::size_t>(c.motion);
    const ir::BodyMotion& body = snapshot_.bodies[motion];
    const Vec3 n = render::BlendNormal(previous_n_[i], c.n_W, alpha);
    rendered_n_[i] = n;
    render::SphereContact contact;
    Vec3 p_WCm;
    if (body.has_dynamics) {
      contact = local()[motion].TouchSphere(c.p_BC, n, in.X_WP.p, in.V_WP, radius_, g.stiffness,
                                            g.damping);
      p_WCm = local()[motion].p_WCm();
    } else {
      const render::BlendedPoint o = render::BlendBodyPoint(body, c.p_BC, alpha);
      p_WCm = o.p_WCm;
      contact = render::TouchSpherePlane(o.p_WO, o.v_WO, n, in.X_WP.p, in.V_WP, radius_,
                                         g.stiffness, g.damping);
    }
    if (contact.result.magnitude <= 0.0) continue;
    const Vec3& f_d = contact.result.f_W;
    ++out->contacts;
    transients_.Touch(c.geom, contact.state.n_W, render::ApproachSpeed(contact),
                      c.material.vibration);
    const Wrench w = render::PointerWrench(contact, in.X_WP.p);
    out->w_W.f += w.f;
    out->w_W.tau += w.tau;
    if (!body.is_static) {
      // eq. 4.12: the object receives −f_d at its plane point.
      tick_force_[motion] -= f_d;
      tick_torque_[motion] += (contact.state.p_WO - p_WCm).cross(-f_d);
    }
  }
}

// eq. 4.14–4.15 with this tick's reaction, and the period's impulse bookkeeping: the last
// reaction force becomes the next perturbation force (thesis §4.3.2, §4.2.2).
void LocalDynamicsHaptic::StepLocalBodies(const TickInput& in, TickOutput* out) noexcept {
  for (ir::BodyImpulse& entry : period_.impulses) entry.last_force = Vec3::Zero();
  for (std::size_t b = 0; b < snapshot_.bodies.size(); ++b) {
    if (snapshot_.bodies[b].has_dynamics && !local()[b].Step(tick_force_[b], in.dt)) {
      ++haptic_counters_.local_faults;
      out->status |= kLocalBodyFault;
    }
    if (tick_force_[b].isZero(0.0) && tick_torque_[b].isZero(0.0)) continue;
    period_.AddImpulse(snapshot_.bodies[b].body, tick_force_[b] * in.dt, tick_torque_[b] * in.dt,
                       tick_force_[b]);
  }
}

void LocalDynamicsHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  report->local_states.Clear();
  for (std::size_t b = 0; b < snapshot_.bodies.size(); ++b) {
    const ir::BodyMotion& m = snapshot_.bodies[b];
    if (!m.has_dynamics) continue;
    if (!report->local_states.PushBack(
            ir::LocalBodyState{m.body, local()[b].X_WB(), local()[b].V_WCm()})) {
      period_.status |= ir::kStatusBodiesFull;
    }
  }
  report->status |= period_.status;
  period_.impulses.Clear();
  period_.status = ir::kStatusOk;
}

const render::LocalBody* LocalDynamicsHaptic::local_body(int body) const noexcept {
  for (std::size_t b = 0; b < snapshot_.bodies.size(); ++b) {
    if (snapshot_.bodies[b].body == body && snapshot_.bodies[b].has_dynamics) return &local()[b];
  }
  return nullptr;
}

}  // namespace mrh::haptic::internal
