// SPDX-License-Identifier: Apache-2.0
// Physics half of local-dynamics: synchronization, global step, IR and perturbations (thesis
// §4.1.3, fig. 4.5).
#include "local_dynamics_physics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "mrh/world/world.h"

namespace mrh::physics::internal {
namespace {

// A user force below this (N) is no usable test force: the perturbed velocities would be
// dominated by solver tolerance. The nominal force along −n is used instead (the thesis leaves
// the zero-force case open).
constexpr double kMinUserForce = 1e-3;

Vec6 ToVec6(const Twist& t) {
  Vec6 out;
  out << t.v, t.w;
  return out;
}

Mat3 Cross(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

}  // namespace

LocalDynamicsPhysics::LocalDynamicsPhysics(const MethodContext& context,
                                           const LocalDynamicsOptions& options)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt),
      rendering_(context.settings->rendering),
      correction_(rendering_.perturbation ? options.correction
                                          : CorrectionModel::kVelocityResidual),
      perturber_(context.world, options.perturber) {
  builder_.emplace(*world_, pointer_body_, PointerRadiusFor3Dof(context), rendering_);
  if (options.reference.has_value() && rendering_.perturbation) {
    reference_.emplace(context.world, *options.reference);
  }
  const auto capacity = static_cast<std::size_t>(world_->num_bodies());
  sent_last_.reserve(capacity);
  sent_before_.reserve(capacity);
  sync_failed_.reserve(capacity);
  targets_.reserve(capacity);
  target_bodies_.reserve(capacity);
  measured_.reserve(capacity);
}

void LocalDynamicsPhysics::PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_body_, initial.X_WP);
  builder_->CapturePreviousPoses(*world_);
  builder_->Build(*world_, initial.X_WP, out);
  FindTargets(nullptr, *out);
  MeasureTargets(out);
  FillDynamics(out);
  out->step = -1;
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

// Inside physics step k (thesis §4.1.3, fig. 4.5, with the overwrite of eq. 4.16–4.17 done at
// the step's start): (0) overwrite, (1) global step recording f_n, (2) neighbor search and IR,
// (3) perturbations, (4) fill the snapshot.
void LocalDynamicsPhysics::PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) {
  LocalDynamicsTiming& last = counters_.last;
  auto t0 = std::chrono::steady_clock::now();
  Overwrite(report);
  last.overwrite_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  GlobalStep(report);
  last.global_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  builder_->Build(*world_, report.X_WP, out);
  last.ir_ms = MsSince(t0);
  FindTargets(&report, *out);
  MeasureTargets(out);
  FillDynamics(out);
  out->t = world_->time();
  out->physics_dt = physics_dt_;
  ++counters_.steps;
  counters_.total.overwrite_ms += last.overwrite_ms;
  counters_.total.global_ms += last.global_ms;
  counters_.total.ir_ms += last.ir_ms;
  counters_.total.perturbation_ms += last.perturbation_ms;
}

const LocalDynamicsPhysics::SentBody* LocalDynamicsPhysics::FindSent(
    const std::vector<SentBody>& sent, int body) const {
  for (const SentBody& s : sent) {
    if (s.body == body) return &s;
  }
  return nullptr;
}

// (1) The global step, without the user's force (it reaches the neighbors only through the
// overwrite of eq. 4.16–4.17; applying it here too would count it twice), recording each dynamic
// neighbor's velocity correction for eq. 4.18 (CorrectionModel).
void LocalDynamicsPhysics::GlobalStep(const ir::HapticReport& report) {
  const bool residual = correction_ == CorrectionModel::kVelocityResidual;
  if (residual) {
    for (SentBody& s : sent_last_) s.u_before = world_->body_state(s.body).V_WCm;
  }
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  world_->Step();
  if (!residual) {
    // Before any query refreshes the kinematics: the step's own contacts and forces.
    for (SentBody& s : sent_last_) {
      s.dV_n = perturber_.NewContactVelocityChange(s.body, known_contacts_);
    }
    return;
  }
  for (SentBody& s : sent_last_) {
    const Vec6 du = ToVec6(world_->body_state(s.body).V_WCm) - ToVec6(s.u_before);
    const Vec6 dV = du - s.b * physics_dt_;
    s.dV_n = Twist{dV.head<3>(), dV.tail<3>()};
  }
}

// Every dynamic neighbor with its nearest contact's plane point and the first test force: the
// reaction the user applied at the end of the last period (thesis §4.2.2), or the nominal force
// into the object when there is none.
void LocalDynamicsPhysics::FindTargets(const ir::HapticReport* report,
                                       const ir::PhysicsSnapshot& out) {
  targets_.clear();
  for (std::size_t m = 0; m < out.bodies.size(); ++m) {
    const ir::BodyMotion& motion = out.bodies[m];
    if (motion.is_static) continue;
    Target t;
    t.motion = m;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < out.contacts.size(); ++c) {
      const ir::PointContact& contact = out.contacts[c];
      if (contact.motion != static_cast<int>(m) || !(contact.distance < nearest)) continue;
      nearest = contact.distance;
      t.contact = static_cast<int>(c);
    }
    if (t.contact < 0) continue;
    const ir::PointContact& contact = out.contacts[static_cast<std::size_t>(t.contact)];
    t.p_W = motion.X_WB * contact.p_BC;
    t.f1 = -rendering_.perturbation_force * contact.n_W;
    if (report != nullptr) {
      for (const ir::BodyImpulse& impulse : report->impulses) {
        if (impulse.body == motion.body && impulse.last_force.norm() >= kMinUserForce) {
          t.f1 = impulse.last_force;
        }
      }
    }
    // A degenerate contact normal (or an absurd force) measures nothing: skip the target.
    if (!(t.f1.allFinite() && t.f1.norm() > 0.0)) continue;
    targets_.push_back(t);
  }
}

// (3) Perturbation runs: one shared zero-force run (it gives every target's b), then three per
// target (eq. 4.3–4.10).
void LocalDynamicsPhysics::MeasureTargets(ir::PhysicsSnapshot* out) {
  const auto t0 = std::chrono::steady_clock::now();
  measured_.clear();
  if (rendering_.perturbation && !targets_.empty()) {
    target_bodies_.clear();
    for (const Target& t : targets_) target_bodies_.push_back(out->bodies[t.motion].body);
    perturber_.Begin(target_bodies_);
    perturber_.ZeroForceRun();
    const std::span<const std::uint64_t> contacts = perturber_.base_contacts();
    known_contacts_.assign(contacts.begin(), contacts.end());
    measured_groups_.clear();
    measured_group_start_.clear();
    for (std::size_t i = 0; i < targets_.size(); ++i) {
      measured_.push_back(perturber_.Measure(i, targets_[i].f1, targets_[i].p_W));
      measured_group_start_.push_back(measured_groups_.size());
      const std::span<const world::GroupResponse> group = perturber_.group();
      measured_groups_.insert(measured_groups_.end(), group.begin(), group.end());
    }
    measured_group_start_.push_back(measured_groups_.size());
    perturber_.End();
    if (reference_.has_value()) CheckAgainstReference();
  }
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const int body = out->bodies[targets_[i].motion].body;
    if (i == measured_.size()) {
      measured_.push_back(OwnAccelerance(body, targets_[i].p_W));
      ++counters_.own_accelerance;
    } else if (!measured_[i].A.allFinite() || !measured_[i].b.allFinite()) {
      measured_[i] = OwnAccelerance(body, targets_[i].p_W);
      ++counters_.own_accelerance;
    }
  }
  counters_.perturbed_bodies += static_cast<std::int64_t>(targets_.size());
  counters_.last_perturbed_bodies = static_cast<int>(targets_.size());
  counters_.last.perturbation_ms = MsSince(t0);
}

// The same measurements by the reference perturber, from the same (restored) state.
void LocalDynamicsPhysics::CheckAgainstReference() {
  reference_->Begin(target_bodies_);
  reference_->ZeroForceRun();
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const world::DynamicIr ref = reference_->Measure(i, targets_[i].f1, targets_[i].p_W);
    const double rel_A = (measured_[i].A - ref.A).norm() / ref.A.norm();
    const double rel_b = (measured_[i].b - ref.b).norm() / (1.0 + ref.b.norm());
    ++counters_.reference_checks;
    counters_.reference_max_rel_A = std::max(counters_.reference_max_rel_A, rel_A);
    counters_.reference_sum_rel_A += rel_A;
    counters_.reference_max_rel_b = std::max(counters_.reference_max_rel_b, rel_b);
  }
  reference_->End();
}

// A = M⁻¹J of the body alone for a force at p_W (eq. 4.1–4.2 without what it touches), b = 0:
// the "without perturbations" variant, and the fallback for a failed measurement.
world::DynamicIr LocalDynamicsPhysics::OwnAccelerance(int body, const Vec3& p_W) const {
  const world::BodyInfo& info = world_->body(body);
  const world::BodyState state = world_->body_state(body);
  const Mat3 R = state.X_WB.q.toRotationMatrix();
  world::DynamicIr ir;
  ir.A.topRows<3>() = Mat3::Identity() / info.mass;
  ir.A.bottomRows<3>() = (R * info.inertia_B * R.transpose()).inverse() * Cross(p_W - state.p_WCm);
  return ir;
}

// (4) Dynamic IR into the snapshot, and the bookkeeping for the next two steps.
void LocalDynamicsPhysics::FillDynamics(ir::PhysicsSnapshot* out) {
  sent_before_.swap(sent_last_);
  sent_last_.clear();
  group_before_.swap(group_last_);
  group_last_.clear();
  const bool with_groups = rendering_.perturbation && !targets_.empty();
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const Target& t = targets_[i];
    ir::BodyMotion& motion = out->bodies[t.motion];
    motion.has_dynamics = true;
    motion.A = measured_[i].A;
    motion.b = measured_[i].b;
    motion.p_BA = out->contacts[static_cast<std::size_t>(t.contact)].p_BC;
    // The period now rendering this body continues into the next one, unless the world could
    // not take its state.
    const SentBody* previous = FindSent(sent_before_, motion.body);
    bool failed = false;
    for (int b : sync_failed_) failed = failed || b == motion.body;
    motion.continues = previous != nullptr && !failed;
    motion.dV_n = motion.continues ? previous->dV_n : Twist{};
    SentBody sent;
    sent.body = motion.body;
    sent.A = motion.A;
    sent.b = motion.b;
    sent.dV_sent = motion.dV_n;
    sent.first_member = group_last_.size();
    if (with_groups) {
      group_last_.insert(
          group_last_.end(),
          measured_groups_.begin() + static_cast<std::ptrdiff_t>(measured_group_start_[i]),
          measured_groups_.begin() + static_cast<std::ptrdiff_t>(measured_group_start_[i + 1]));
    }
    sent.members = group_last_.size() - sent.first_member;
    sent_last_.push_back(sent);
  }
}

}  // namespace mrh::physics::internal
