// SPDX-License-Identifier: Apache-2.0
// proxy-6dof's reaction from a physics-side proxy run against the objects' predicted poses.
#include "proxy_local_reaction.h"

#include <algorithm>
#include <cmath>

#include "mrh/world/world.h"
#include "pointer_ahead.h"

namespace mrh::physics::internal {

ProxyLocalReaction::ProxyLocalReaction(world::World& world, int pointer_body,
                                       const settings::RenderingSettings& rendering,
                                       const render::ProxyRendererSettings& settings,
                                       double physics_dt, double haptic_dt)
    : exporter_(&world),
      model_(std::make_unique<ir::LocalContactModel>()),
      physics_dt_(physics_dt),
      substeps_(std::max(1, static_cast<int>(std::lround(physics_dt / haptic_dt)))) {
  const auto capacity = static_cast<std::size_t>(world.num_bodies());
  seeds_.reserve(capacity);
  motions_.reserve(capacity);
  AddPointer(world, pointer_body, rendering, settings);
}

ProxyLocalReaction::PointerRun::PointerRun(world::World& world, int pointer_body,
                                           const settings::RenderingSettings& rendering,
                                           const render::ProxyRendererSettings& settings)
    : builder(world, pointer_body, rendering), renderer(settings) {}

void ProxyLocalReaction::AddPointer(world::World& world, int pointer_body,
                                    const settings::RenderingSettings& rendering,
                                    const render::ProxyRendererSettings& settings) {
  pointers_.push_back(std::make_unique<PointerRun>(world, pointer_body, rendering, settings));
}

ProxyLocalReaction::LocalBody* ProxyLocalReaction::Find(int body) {
  for (LocalBody& b : bodies_) {
    if (b.body == body) return &b;
  }
  return nullptr;
}

// The rest of the world's wrench on the body during its last step, as accelerations: the
// velocity change the applied reaction does not explain. Zero for a body not touched then.
void ProxyLocalReaction::EstimateOtherWrench(LocalBody* body) const {
  for (const BodyMemory& m : memory_) {
    if (m.body != body->body) continue;
    const Mat3 R = body->q.toRotationMatrix();
    const Mat3 inertia_W = R * body->inertia_B * R.transpose();
    body->a_other = (body->v - m.v) / physics_dt_ - m.impulse.f / (body->mass * physics_dt_);
    body->alpha_other =
        (body->w - m.w) / physics_dt_ - inertia_W.inverse() * m.impulse.tau / physics_dt_;
    return;
  }
}

void ProxyLocalReaction::StartBodies(const world::World& world) {
  bodies_.Clear();
  for (const std::unique_ptr<PointerRun>& run : pointers_) {
    for (const render::TickPair& pair : run->base.pairs) {
      if (pair.is_static || pair.body < 0 || Find(pair.body) != nullptr) continue;
      const world::BodyInfo& info = world.body(pair.body);
      const world::BodyState state = world.body_state(pair.body);
      LocalBody b;
      b.body = pair.body;
      b.mass = info.mass;
      b.inertia_B = info.inertia_B;
      b.p_BCm = info.p_BCm;
      b.q = state.X_WB.q.normalized();
      b.com = state.p_WCm;
      b.com0 = state.p_WCm;
      b.v = state.V_WCm.v;
      b.w = state.V_WCm.w;
      b.q0 = b.q;
      b.v0 = b.v;
      b.w0 = b.w;
      EstimateOtherWrench(&b);
      if (!(b.mass > 0.0) || !bodies_.PushBack(b)) continue;
    }
  }
}

// The touched free bodies' contact island into solver_, from the world as it is now.
void ProxyLocalReaction::StartIsland() {
  seeds_.clear();
  motions_.clear();
  for (const LocalBody& b : bodies_) {
    if (!exporter_.IsFreeBody(b.body)) continue;
    seeds_.push_back(b.body);
    motions_.push_back(static_cast<int>(motions_.size()));
  }
  if (seeds_.empty()) {
    solver_.Clear();
    return;
  }
  (void)exporter_.Export(seeds_, motions_, model_.get());
  // Every body from the world's state (the world owns it between steps; AfterStep writes the
  // run back), the contacts warm-started from the last step's impulses: with one substep per
  // step a solve started from zero stops at its sweep cap with the floor friction unresolved.
  solver_.Restart(*model_);
  for (LocalBody& b : bodies_) {  // local is -1 from StartBodies
    for (std::size_t i = 0; i < solver_.size(); ++i) {
      if (solver_.world_body(i) == b.body) b.local = static_cast<int>(i);
    }
  }
}

// run.ir = run.base with every touched object at its local pose and the points at pointer pose
// X_WP.
void ProxyLocalReaction::PoseIr(PointerRun& run, const Pose& X_WP) {
  run.ir = run.base;
  for (render::TickPair& pair : run.ir.pairs) {
    const LocalBody* b = pair.is_static ? nullptr : Find(pair.body);
    if (b == nullptr) continue;
    const Quat dq = b->q * pair.X_WB.q.normalized().conjugate();
    pair.n_W = (dq * pair.n_W).normalized();
    pair.X_WB = Pose{b->com - b->q * b->p_BCm, b->q};
    pair.c_W = pair.X_WB * pair.p_BC;
    pair.p_WCm = b->com;
  }
  for (render::TickPoint& point : run.ir.points) {
    const render::TickPair& pair = run.ir.pairs[static_cast<std::size_t>(point.pair)];
    point.v_W = X_WP * point.p_PV;
    point.depth = pair.n_W.dot(pair.c_W - point.v_W);
  }
}

// Every pointer's reaction on world body `body` this substep, about its current COM.
Wrench ProxyLocalReaction::ReactionOn(int body) const noexcept {
  Wrench w;
  for (const std::unique_ptr<PointerRun>& run : pointers_) {
    for (const render::ProxyPairReaction& r : run->output.reactions) {
      if (r.is_static || r.body != body) continue;
      w.f += r.w_W.f;
      w.tau += r.w_W.tau;
    }
  }
  return w;
}

// One renderer tick of length h per pointer (pointer i at its report's pose moved on to time t
// of the step), then each touched body moves under all its reactions and the rest of the
// world's wrench (semi-implicit Euler, as MuJoCo's).
void ProxyLocalReaction::Substep(double h, std::span<const ir::HapticReport* const> reports,
                                 double t) {
  for (std::size_t i = 0; i < pointers_.size(); ++i) {
    PointerRun& run = *pointers_[i];
    const Pose X_WP = PointerAhead(*reports[i], t);
    PoseIr(run, X_WP);
    run.renderer.Tick(run.ir, X_WP, h, &run.output);
    run.impulse.f += run.output.w_W.f * h;
    run.impulse.tau += (run.output.w_W.tau + (X_WP.p - run.origin).cross(run.output.w_W.f)) * h;
  }
  for (LocalBody& b : bodies_) {
    const Wrench w = ReactionOn(b.body);  // on the body, about its current COM
    b.last_force = w.f;
    b.impulse.f += w.f * h;
    b.impulse.tau += (w.tau + (b.com - b.com0).cross(w.f)) * h;
    if (b.local >= 0) {
      const auto i = static_cast<std::size_t>(b.local);
      solver_.AddForce(i, w.f, b.com);
      solver_.AddTorque(i, w.tau);
      island_touched_ = island_touched_ || !(w.f.isZero(0.0) && w.tau.isZero(0.0));
      continue;
    }
    const Mat3 R = b.q.toRotationMatrix();
    const Mat3 inertia_W = R * b.inertia_B * R.transpose();
    b.v += h * (w.f / b.mass + b.a_other);
    b.w += h * (inertia_W.inverse() * w.tau + b.alpha_other);
    b.com += h * b.v;
    b.q = (QuatFromRotationVector(h * b.w) * b.q).normalized();
  }
  if (solver_.size() == 0) return;
  (void)solver_.Step(h);  // a non-finite body is held (LocalContactSolver::Step)
  for (LocalBody& b : bodies_) {
    if (b.local < 0) continue;
    const auto i = static_cast<std::size_t>(b.local);
    b.com = solver_.p_WCm(i);
    b.q = solver_.X_WB(i).q.normalized();
    b.v = solver_.V_WCm(i).v;
    b.w = solver_.V_WCm(i).w;
  }
}

// The impulse that gives the world's body the reaction's share of the local run's displacement.
// MuJoCo's semi-implicit step moves a body by its end-of-step velocity, so J sets that velocity
// to the local run's mean velocity less the mean the rest of the world's wrench alone gives
// over the substeps (v0 + a h (n + 1)/2); the world step adds that wrench itself. Rotation
// likewise, to first order.
Wrench ProxyLocalReaction::DisplacementImpulse(const LocalBody& b) const {
  const double h = physics_dt_ / substeps_;
  const double other = h * (substeps_ + 1) / 2.0;
  const Vec3 v_mean = (b.com - b.com0) / physics_dt_;
  const Vec3 w_mean = RotationVectorFromQuat((b.q * b.q0.conjugate()).normalized()) / physics_dt_;
  const Mat3 R = b.q0.toRotationMatrix();
  const Mat3 inertia_W = R * b.inertia_B * R.transpose();
  return Wrench{b.mass * (v_mean - b.v0 - other * b.a_other),
                inertia_W * (w_mean - b.w0 - other * b.alpha_other)};
}

void ProxyLocalReaction::Finish(world::World& world) {
  applied_.impulses.Clear();
  proxy_.impulses.Clear();
  memory_.Clear();
  for (const LocalBody& b : bodies_) {
    const bool touched = !(b.impulse.f.isZero(0.0) && b.impulse.tau.isZero(0.0));
    if (b.local >= 0) {  // AfterStep sets it (and its island): the world receives the reaction
      if (touched) {
        proxy_.AddImpulse(b.body, b.impulse.f, b.impulse.tau, b.last_force);
        applied_.AddImpulse(b.body, b.impulse.f, b.impulse.tau, b.last_force);
      }
      (void)memory_.PushBack(BodyMemory{b.body, b.v, b.w, Wrench{}});
      continue;
    }
    const Wrench J = touched ? DisplacementImpulse(b) : Wrench{};
    const world::BodyState state = world.body_state(b.body);
    (void)memory_.PushBack(BodyMemory{b.body, state.V_WCm.v, state.V_WCm.w, J});
    if (!touched) continue;
    proxy_.AddImpulse(b.body, b.impulse.f, b.impulse.tau, b.last_force);
    world.AddWrenchAtCom(b.body, Wrench{J.f / physics_dt_, J.tau / physics_dt_});
    applied_.AddImpulse(b.body, J.f, J.tau, b.last_force);
  }
}

void ProxyLocalReaction::Apply(world::World& world, const ir::HapticReport& report) {
  const ir::HapticReport* const one[] = {&report};
  Apply(world, one);
}

void ProxyLocalReaction::Apply(world::World& world,
                               std::span<const ir::HapticReport* const> reports) {
  // The pointer during this step: the report's pose moved on with the report's velocity. The IR
  // of the objects as they are now, for the pointer where it will be at the step's end, so the
  // contact points cover the region it will penetrate (the snapshot's IR, built for the
  // report's pose, may hold only a closest point when the pointer is just arriving).
  for (std::size_t i = 0; i < pointers_.size(); ++i) {
    PointerRun& run = *pointers_[i];
    run.impulse = Wrench{};
    run.origin = reports[i]->X_WP.p;
    const Pose X_WP_end = PointerAhead(*reports[i], physics_dt_);
    run.snapshot->status = ir::kStatusOk;
    run.builder.CapturePreviousPoses(world);
    run.builder.Build(world, X_WP_end, run.snapshot.get());
    run.interpolator.Adopt(*run.snapshot);
    run.interpolator.Evaluate(1.0, X_WP_end, &run.base);
  }
  StartBodies(world);
  StartIsland();
  island_touched_ = false;
  const double h = physics_dt_ / substeps_;
  for (int s = 0; s < substeps_; ++s) Substep(h, reports, (s + 1) * h);
  Finish(world);
}

void ProxyLocalReaction::AfterStep(world::World& world) {
  if (!island_touched_) return;
  for (std::size_t i = 0; i < solver_.size(); ++i) {
    (void)world.SetBodyState(solver_.world_body(i), solver_.X_WB(i), solver_.V_WCm(i));
  }
}

}  // namespace mrh::physics::internal
