// SPDX-License-Identifier: Apache-2.0
// Haptic half of local-dynamics: local simulation of the neighbors and 3-DOF penalty rendering.
#include <algorithm>

#include "local_dynamics_haptic.h"
#include "normal_carry.h"

namespace mrh::haptic::internal {

// A body that continues keeps its local state (the local simulation owns it while it stays a
// neighbor, SPEC §4.4) and gets the correction of eq. 4.18 at its first tick; a new neighbor
// starts from the global state. Normals blend from the last rendered one (SPEC §4.6).
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
  const double alpha = std::min(1.0, static_cast<double>(in.j + 1) / static_cast<double>(in.n));
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
  StepLocalBodies(in, out);
  ++haptic_counters_.ticks;
}

// Corrected eq. 4.11 against every contact's plane: on a dynamic neighbor the plane moves with
// its local body; a static or kinematic body is blended between its step poses as in B4.
void LocalDynamicsHaptic::RenderContacts(const TickInput& in, double alpha,
                                         TickOutput* out) noexcept {
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) {
    const ir::PointContact& c = snapshot_.contacts[i];
    const auto motion = static_cast<std::size_t>(c.motion);
    const ir::BodyMotion& body = snapshot_.bodies[motion];
    Vec3 n = (1.0 - alpha) * previous_n_[i] + alpha * c.n_W;
    n.normalize();
    rendered_n_[i] = n;
    render::SphereContact contact;
    Vec3 p_WCm;
    if (body.has_dynamics) {
      contact =
          local()[motion].TouchSphere(c.p_BC, n, in.X_WP.p, in.V_WP, radius_, stiffness_, damping_);
      p_WCm = local()[motion].p_WCm();
    } else {
      const Pose X_WB = Interpolate(body.X_WB_prev, body.X_WB, alpha);
      p_WCm = X_WB * body.p_BCm;
      contact.state.p_WO = X_WB * c.p_BC;
      contact.state.n_W = n;
      contact.state.v_WO = body.V_WCm.v + body.V_WCm.w.cross(contact.state.p_WO - p_WCm);
      contact.state.p_WC = in.X_WP.p - radius_ * n;
      contact.state.v_WC = in.V_WP.v + in.V_WP.w.cross(contact.state.p_WC - in.X_WP.p);
      contact.result = render::RenderPointPenalty(contact.state, stiffness_, damping_);
    }
    if (contact.result.magnitude <= 0.0) continue;
    const Vec3& f_d = contact.result.f_W;
    ++out->contacts;
    out->w_W.f += f_d;
    out->w_W.tau += (contact.state.p_WC - in.X_WP.p).cross(f_d);
    if (!body.is_static) {
      // eq. 4.12: the object receives −f_d at its plane point.
      tick_force_[motion] -= f_d;
      tick_torque_[motion] += (contact.state.p_WO - p_WCm).cross(-f_d);
    }
  }
}

// eq. 4.14–4.15 with this tick's reaction, and the period's impulse bookkeeping: the last
// reaction force becomes the next perturbation force (SPEC §4.7).
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
