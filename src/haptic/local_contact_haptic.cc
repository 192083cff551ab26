// SPDX-License-Identifier: Apache-2.0
// local-dynamics, contact local model, haptic half: the island at 1 kHz and 3-DOF penalty
// rendering against planes fixed on its bodies.
#include "local_contact_haptic.h"

#include <algorithm>

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
  if (owner_ == nullptr) {
    solver_.Adopt(snapshot_.local_model);
    adopted_step_ = snapshot_.step;
  }
  MapMotions();
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) {
    const ir::PointContact& c = snapshot_.contacts[i];
    n_B_[i] = snapshot_.bodies[static_cast<std::size_t>(c.motion)].X_WB.q.conjugate() * c.n_W;
    rendered_n_[i] = previous_n_[i];
  }
}

void LocalContactHaptic::MapMotions() noexcept {
  const std::int64_t island_step = owner_ ? owner_->adopted_step_ : adopted_step_;
  const bool current = island_step == snapshot_.step;
  for (std::size_t m = 0; m < snapshot_.bodies.size(); ++m) {
    local_of_motion_[m] = current ? island().FindMotion(static_cast<int>(m)) : -1;
  }
  mapped_step_ = current ? island_step : -2;
}

namespace {

// The tangent plane of a round object (sphere, capsule) facing the pointer centre p_WP: normal
// from the core point nearest p_WP, point on the surface. Keeps n_W and p_WO when p_WP is on
// the core (no direction).
void RoundPlane(const Pose& X_WB, const ir::PointContact& c, const Vec3& p_WP, Vec3* n_W,
                Vec3* p_WO) noexcept {
  const Vec3 a = X_WB * c.core_B[0];
  const Vec3 ab = X_WB * c.core_B[1] - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p_WP - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  const Vec3 core = a + s * ab;
  const Vec3 dir = p_WP - core;
  const double len = dir.norm();
  if (!(len > 1e-12)) return;
  *n_W = dir / len;
  *p_WO = core + c.r * *n_W;
}

}  // namespace

void LocalContactHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const double alpha = in.alpha();
  out->w_W = Wrench{};
  out->contacts = 0;
  out->status = 0;
  for (ir::BodyImpulse& entry : period_.impulses) entry.last_force = Vec3::Zero();
  // A follower whose snapshot and the island's model came a tick apart catches up here.
  if (owner_ != nullptr && mapped_step_ != snapshot_.step) MapMotions();
  RenderContacts(in, alpha, out);
  if (friction_ > 0.0) anchors_.ReleaseUntouched();
  render::AddTransientForce(in.dt, &transients_, &out->w_W.f);
  if (steps_ && !island().Step(in.dt)) {
    ++counters_.local_faults;
    out->status |= kLocalBodyFault;
  }
  ++counters_.ticks;
}

// Contact i's plane this tick (normal n_W through p_WO, moving at v_WO) and its body's COM
// p_WCm: from the island's state for an island body, else blended over the period.
void LocalContactHaptic::ContactPlane(std::size_t i, const TickInput& in, double alpha, Vec3* n_W,
                                      Vec3* p_WO, Vec3* v_WO, Vec3* p_WCm) noexcept {
  const ir::PointContact& c = snapshot_.contacts[i];
  const auto motion = static_cast<std::size_t>(c.motion);
  const int local = local_of_motion_[motion];
  if (local >= 0) {
    render::LocalContactSolver& solver = island();
    const auto l = static_cast<std::size_t>(local);
    const Pose X_WB = solver.X_WB(l);
    *n_W = X_WB.q * n_B_[i];
    *p_WO = X_WB * c.p_BC;
    if (c.r > 0.0) RoundPlane(X_WB, c, in.X_WP.p, n_W, p_WO);
    *v_WO = solver.PointVelocity(l, *p_WO);
    *p_WCm = solver.p_WCm(l);
  } else {
    *n_W = render::BlendNormal(previous_n_[i], c.n_W, alpha);
    const render::BlendedPoint o = render::BlendBodyPoint(snapshot_.bodies[motion], c.p_BC, alpha);
    *p_WO = o.p_WO;
    *v_WO = o.v_WO;
    *p_WCm = o.p_WCm;
  }
}

// Corrected eq. 4.11 against every contact's plane; the reaction (eq. 4.12) goes to the island
// body in this tick, or, for a body outside the island, into the period's impulse.
void LocalContactHaptic::RenderContacts(const TickInput& in, double alpha,
                                        TickOutput* out) noexcept {
  for (std::size_t i = 0; i < snapshot_.contacts.size(); ++i) {
    const ir::PointContact& c = snapshot_.contacts[i];
    // The geom's material, or rendering.*.
    const ir::ContactGains g = ir::GainsOf(c.material, {stiffness_, damping_, friction_});
    const auto motion = static_cast<std::size_t>(c.motion);
    const ir::BodyMotion& body = snapshot_.bodies[motion];
    const int local = local_of_motion_[motion];
    Vec3 n_W, p_WO, v_WO, p_WCm;
    render::LocalContactSolver& solver = island();
    ContactPlane(i, in, alpha, &n_W, &p_WO, &v_WO, &p_WCm);
    rendered_n_[i] = n_W;
    const render::SphereContact contact = render::TouchSpherePlane(
        p_WO, v_WO, n_W, in.X_WP.p, in.V_WP, radius_, g.stiffness, g.damping);
    if (contact.result.magnitude <= 0.0) continue;
    Vec3 f_d = contact.result.f_W;
    ++out->contacts;
    transients_.Touch(c.geom, contact.state.n_W, render::ApproachSpeed(contact),
                      c.material.vibration);
    Wrench w = render::PointerWrench(contact, in.X_WP.p);
    if (friction_ > 0.0 && g.friction > 0.0) {
      const Pose X_WB = local >= 0 ? solver.X_WB(static_cast<std::size_t>(local))
                                   : Interpolate(body.X_WB_prev, body.X_WB, alpha);
      const Vec3 f_t = anchors_.Friction(c.geom, X_WB, contact.state.p_WC, contact.state.n_W,
                                         g.stiffness, g.friction, contact.result.magnitude);
      f_d += f_t;
      w.f += f_t;
      w.tau += (contact.state.p_WC - in.X_WP.p).cross(f_t);
    }
    out->w_W.f += w.f;
    out->w_W.tau += w.tau;
    if (body.is_static) continue;
    if (local >= 0) solver.AddForce(static_cast<std::size_t>(local), -f_d, p_WO);
    period_.AddImpulse(body.body, -f_d * in.dt, (p_WO - p_WCm).cross(-f_d) * in.dt, -f_d);
  }
}

void LocalContactHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  report->local_states.Clear();
  // Several pointers: the half that steps the island reports its end states, once.
  const render::LocalContactSolver& solver = island();
  for (std::size_t i = 0; steps_ && i < solver.size(); ++i) {
    if (!report->local_states.PushBack(
            ir::LocalBodyState{solver.world_body(i), solver.X_WB(i), solver.V_WCm(i)})) {
      period_.status |= ir::kStatusBodiesFull;
    }
  }
  report->status |= period_.status;
  period_.impulses.Clear();
  period_.status = ir::kStatusOk;
}

}  // namespace mrh::haptic::internal
