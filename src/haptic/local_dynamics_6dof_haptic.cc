// SPDX-License-Identifier: Apache-2.0
// local-dynamics-6dof, haptic half: the 6-DOF proxy against planes that ride on the locally
// simulated neighbors, its reaction pushing them in the same tick.
#include "local_dynamics_6dof_haptic.h"

#include <cmath>

namespace mrh::haptic::internal {
LocalDynamics6dofHaptic::LocalDynamics6dofHaptic(const render::ProxyRendererSettings& settings,
                                                 const render::LocalContactSolverSettings& solver)
    : renderer_(settings), solver_(solver) {
  local_of_motion_.fill(-1);
}

// The interpolator emits one tick pair per snapshot pair with a valid motion, in order; n_F_
// follows that order.
void LocalDynamics6dofHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  interpolator_.Adopt(snapshot);
  if (owner_ == nullptr) {
    solver_.Adopt(snapshot.local_model);
    adopted_step_ = snapshot.step;
  }
  snapshot_step_ = snapshot.step;
  snapshot_bodies_ = snapshot.bodies.size();
  MapMotions();
  std::size_t j = 0;
  for (const ir::GeometricPair& pair : snapshot.pairs) {
    if (pair.motion < 0 || static_cast<std::size_t>(pair.motion) >= snapshot.bodies.size()) {
      continue;
    }
    const ir::BodyMotion& body = snapshot.bodies[static_cast<std::size_t>(pair.motion)];
    c_Cm_[j] = body.X_WB * pair.p_BC - body.X_WB * body.p_BCm;
    const bool carried = pair.n_F.squaredNorm() > 0.0;
    frame_[j] = pair.round                                                  ? Frame::kWorld
                : carried && pair.normal_frame == ir::NormalFrame::kPointer ? Frame::kPointer
                                                                            : Frame::kBody;
    n_F_[j] = pair.round ? pair.n_W : carried ? pair.n_F : Vec3(body.X_WB.q.conjugate() * pair.n_W);
    start_n_F_[j] = n_F_[j];
    const std::uint64_t key = render::PairKey(pair.pointer_geom, pair.object_geom);
    for (std::size_t o = 0; o < rendered_count_; ++o) {
      if (rendered_key_[o] != key) continue;
      start_n_F_[j] = rendered_frame_[o] == frame_[j]
                          ? rendered_n_[o]
                          : InFrame(frame_[j], rendered_n_W_[o], rendered_q_WB_[o]);
      break;
    }
    ++j;
  }
  rendered_count_ = 0;
}

void LocalDynamics6dofHaptic::MapMotions() noexcept {
  const std::int64_t island_step = owner_ ? owner_->adopted_step_ : adopted_step_;
  const bool current = island_step == snapshot_step_;
  local_of_motion_.fill(-1);
  for (std::size_t m = 0; current && m < snapshot_bodies_; ++m) {
    local_of_motion_[m] = island().FindMotion(static_cast<int>(m));
  }
  mapped_step_ = current ? island_step : -2;
}

// Step 2 of the class comment: planes of island pairs on the local poses. The snapshot's normal
// is the contact's at the end of the period it was built for (by the timing rule of thesis
// §4.1.3 and docs/architecture.md: the pointer there, 2 Δt^G after the report). Where the contact
// turns about an edge or a vertex (a round pointer sliding past a corner) that normal is tilted
// from the one at the period's start, and a plane through the corner with it reaches deeper into
// the pointer than the corner does (a plane that supports the contact at one relative pose
// over-estimates the depth at every other); the snapshot switch is then also a step in the load,
// which the damper turns into a one-tick spike. Blending from the last rendered normal keeps the
// normal, and so the depth, continuous and near the contact's own, as IrInterpolator does on the
// other bodies. The blend runs in the frame the normal turns with (the class comment, step 2), so
// the plane still turns with the body whose face it is.
void LocalDynamics6dofHaptic::RePoseOnLocalBodies(double alpha, const Pose& X_WP) noexcept {
  for (std::size_t i = 0; i < tick_ir_.pairs.size(); ++i) {
    render::TickPair& pair = tick_ir_.pairs[i];
    if (pair.is_static || pair.motion < 0) continue;
    const int local = local_of_motion_[static_cast<std::size_t>(pair.motion)];
    if (local < 0) continue;
    const auto l = static_cast<std::size_t>(local);
    pair.X_WB = island().X_WB(l);
    pair.p_WCm = island().p_WCm(l);
    const Vec3 n_F = render::BlendNormal(start_n_F_[i], n_F_[i], alpha);
    switch (frame_[i]) {
      case Frame::kWorld:
        // A rolling round body's surface facing the pointer moves with its centre, unturned: a
        // plane turned with the body would push along its turned normal and drive the roll.
        pair.n_W = n_F;
        pair.c_W = pair.p_WCm + c_Cm_[i];
        break;
      case Frame::kPointer:
        pair.n_W = (X_WP.q * n_F).normalized();
        pair.c_W = pair.X_WB * pair.p_BC;
        break;
      case Frame::kBody:
        pair.n_W = (pair.X_WB.q * n_F).normalized();
        pair.c_W = pair.X_WB * pair.p_BC;
        break;
    }
    const double n_dot_c = pair.n_W.dot(pair.c_W);
    for (int k = pair.first; k < pair.first + pair.count; ++k) {
      render::TickPoint& point = tick_ir_.points[static_cast<std::size_t>(k)];
      point.depth = n_dot_c - pair.n_W.dot(point.v_W);
    }
  }
}

// The normals this tick rendered on island bodies (in their frames, and in the world with the
// pose of their frame, for a pair whose next snapshot names another frame), where the next
// snapshot's blends start. A pair not re-posed this tick (static, or its body not in the
// island) is not remembered: its next snapshot starts from its own normal.
void LocalDynamics6dofHaptic::RememberRenderedNormals(const Pose& X_WP) noexcept {
  rendered_count_ = 0;
  rendered_q_WP_ = X_WP.q;
  for (std::size_t i = 0; i < tick_ir_.pairs.size(); ++i) {
    const render::TickPair& pair = tick_ir_.pairs[i];
    if (pair.is_static || pair.motion < 0 ||
        local_of_motion_[static_cast<std::size_t>(pair.motion)] < 0) {
      continue;
    }
    const std::size_t o = rendered_count_++;
    rendered_key_[o] = pair.key;
    rendered_frame_[o] = frame_[i];
    rendered_n_W_[o] = pair.n_W;
    rendered_q_WB_[o] = pair.X_WB.q;
    rendered_n_[o] = InFrame(frame_[i], pair.n_W, pair.X_WB.q);
  }
}

Vec3 LocalDynamics6dofHaptic::InFrame(Frame frame, const Vec3& n_W,
                                      const Quat& q_WB) const noexcept {
  switch (frame) {
    case Frame::kPointer:
      return rendered_q_WP_.conjugate() * n_W;
    case Frame::kBody:
      return q_WB.conjugate() * n_W;
    case Frame::kWorld:
      break;
  }
  return n_W;
}

// Step 4: each island pair's reaction, the renderer's wrench (the pair's force and its share of
// the proxy's torque, eq. 3.7–3.8, moved to the COM), goes to its local body in the same tick, so
// action = reaction holds in force and in moment with what the user feels, as in proxy-6dof.
// The force alone at the pair's centre of pressure (f_k-weighted points) is not the contact's
// moment: the f_k are offsets in the R_w metric, so its moment about the pointer origin is
// k_t R_w Δθ where the proxy's is k_r Δθ (30× less for t3.6's box pointer); with the force alone
// the box would lose the face's straightening couple and yaw away from an off-centre push.
// The period's impulses record what was applied.
void LocalDynamics6dofHaptic::PushLocalBodies() noexcept {
  for (std::size_t i = 0; i < output_.reactions.size() && i < tick_ir_.pairs.size(); ++i) {
    const render::ProxyPairReaction& r = output_.reactions[i];
    const render::TickPair& pair = tick_ir_.pairs[i];
    if (r.is_static || pair.motion < 0) continue;
    const int local = local_of_motion_[static_cast<std::size_t>(pair.motion)];
    if (local < 0) continue;
    const auto l = static_cast<std::size_t>(local);
    AddWrench(l, r.w_W, island().p_WCm(l));
  }
  render::AddReactionImpulses(output_.reactions, tick_dt_, &period_);
}

// The wrench (force; moment about the COM c) as the force at c plus the couple ±g at c ± a,
// 2 a × g = τ.
void LocalDynamics6dofHaptic::AddWrench(std::size_t l, const Wrench& w, const Vec3& c) noexcept {
  render::LocalContactSolver& solver = island();
  solver.AddForce(l, w.f, c);
  if (!(w.tau.squaredNorm() > 0.0)) return;
  const Vec3 a = w.tau.unitOrthogonal();
  const Vec3 g = 0.5 * w.tau.cross(a);
  solver.AddForce(l, g, c + a);
  solver.AddForce(l, -g, c - a);
}

void LocalDynamics6dofHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  // A follower whose snapshot and the island's model came a tick apart catches up here.
  if (owner_ != nullptr && mapped_step_ != snapshot_step_) MapMotions();
  interpolator_.Evaluate(in.alpha(), in.X_WP, &tick_ir_);
  RePoseOnLocalBodies(in.alpha(), in.X_WP);
  RememberRenderedNormals(in.X_WP);
  renderer_.Tick(tick_ir_, in.X_WP, in.dt, &output_);
  out->w_W = output_.w_W;
  out->X_WQ = output_.X_WQ;
  out->contacts = output_.diagnostics.contacts;
  out->status = output_.diagnostics.status;
  render::TouchPairs(tick_ir_, in.X_WP, in.V_WP, &transients_);
  render::AddTransientForce(in.dt, &transients_, &out->w_W.f);
  tick_dt_ = in.dt;
  PushLocalBodies();
  if (steps_ && !island().Step(in.dt)) out->status |= kLocal6dofBodyFault;
}

void LocalDynamics6dofHaptic::EndPeriod(ir::HapticReport* report) noexcept {
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
