// SPDX-License-Identifier: Apache-2.0
// Baseline B2, physics half: every convex pair's contact-volume penalty, then the world step.
#include "contact_volume_physics.h"

#include <fmt/format.h>

#include <chrono>
#include <optional>

#include "mrh/core/error.h"
#include "mrh/geometry/contact_volume.h"

namespace mrh::physics::internal {
namespace {

// Bounding spheres are grown by this (m) and by this fraction: a curved shape's polyhedron lies
// inside it, while its signed distance is the true surface's.
constexpr double kSphereMargin = 1e-6;
constexpr double kSphereGrowth = 1e-2;

bool Dynamic(const world::BodyInfo& body) {
  return !body.is_static && !body.is_mocap;
}

bool Moves(const world::BodyInfo& body) {
  return !body.is_static || body.is_mocap;
}

}  // namespace

ContactVolumePhysics::ContactVolumePhysics(const MethodContext& context)
    : world_(context.world),
      pointer_(context.pointer_body),
      physics_dt_(context.settings->physics_dt) {
  if (!world_->penalty_contacts()) {
    throw SceneError(fmt::format(
        "{}: contact-volume needs the world loaded with world::LoadOptions::penalty_contacts "
        "(MuJoCo's own contacts off; session::LoadWorld does this for method "
        "\"contact-volume\")",
        world_->origin()));
  }
  const settings::RenderingSettings& r = context.settings->rendering;
  gains_ = PenaltyGains{
      .k = r.stiffness, .d = r.damping, .mu_static = r.friction, .mu_dynamic = r.friction};
  MakePieces(r);
  MakePairs();
  X_WG_.resize(pieces_.size());
}

void ContactVolumePhysics::MakePieces(const settings::RenderingSettings& rendering) {
  for (int g = 0; g < world_->num_geoms(); ++g) {
    const world::GeomInfo& info = world_->geom(g);
    const bool on_pointer = info.body == pointer_;
    if (!on_pointer && !info.collides) continue;
    Piece piece;
    piece.geom = g;
    piece.body = info.body;
    piece.plane = info.shape.type == geometry::ShapeType::kPlane;
    try {
      piece.polyhedron =
          geometry::ConvexPolyhedron::FromShape(info.shape, rendering.curved_segments);
      piece.shape = std::make_unique<geometry::CollisionShape>(info.shape);
    } catch (const Error& e) {
      throw SceneError(fmt::format("{}: geom {} ('{}') of body '{}': {}", world_->origin(), g,
                                   info.name, world_->body(info.body).name, e.what()));
    }
    if (piece.plane && on_pointer) {
      throw SceneError(
          fmt::format("{}: pointer geom {} is a plane; contact-volume needs "
                      "bounded convex pointer geoms",
                      world_->origin(), g));
    }
    for (const Vec3& v : piece.polyhedron.vertices()) {
      piece.radius = std::max(piece.radius, v.norm());
    }
    piece.radius = piece.radius * (1.0 + kSphereGrowth) + kSphereMargin;
    pieces_.push_back(std::move(piece));
  }
}

// Pairs of different bodies that can exert a penalty: one side moves, and one side is a
// dynamic body or the pointer (a mocap body other than the pointer takes no force).
void ContactVolumePhysics::MakePairs() {
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    for (std::size_t j = i + 1; j < pieces_.size(); ++j) {
      const Piece& p = pieces_[i];
      const Piece& q = pieces_[j];
      if (p.body == q.body || (p.plane && q.plane)) continue;
      const world::BodyInfo& bp = world_->body(p.body);
      const world::BodyInfo& bq = world_->body(q.body);
      if (!Moves(bp) && !Moves(bq)) continue;
      const bool forced = Dynamic(bp) || Dynamic(bq) || p.body == pointer_ || q.body == pointer_;
      if (!forced) continue;
      Pair pair;
      pair.a = p.plane ? static_cast<int>(j) : static_cast<int>(i);
      pair.b = p.plane ? static_cast<int>(i) : static_cast<int>(j);
      pairs_.push_back(pair);
    }
  }
}

bool ContactVolumePhysics::Overlap(const Pair& pair) const {
  const auto a = static_cast<std::size_t>(pair.a);
  const auto b = static_cast<std::size_t>(pair.b);
  const Vec3& c_a = X_WG_[a].p;
  if (pieces_[b].plane) {
    const Vec3 n = X_WG_[b].q * Vec3::UnitZ();
    return n.dot(c_a - X_WG_[b].p) <= pieces_[a].radius;
  }
  return (c_a - X_WG_[b].p).norm() <= pieces_[a].radius + pieces_[b].radius;
}

BodyKinematics ContactVolumePhysics::Kinematics(int body, const Twist& V_WP) const {
  const world::BodyState state = world_->body_state(body);
  BodyKinematics k{state.X_WB, state.p_WCm, state.V_WCm};
  if (body == pointer_) {
    k.p_WCm = state.X_WB.p;  // the device twist is of the pointer origin
    k.V_WCm = V_WP;
  } else if (!Dynamic(world_->body(body))) {
    k.V_WCm = Twist{};
  }
  return k;
}

void ContactVolumePhysics::AnalysePair(Pair* pair, const Twist& V_WP) {
  const Piece& a = pieces_[static_cast<std::size_t>(pair->a)];
  const Piece& b = pieces_[static_cast<std::size_t>(pair->b)];
  const Pose& X_WA = X_WG_[static_cast<std::size_t>(pair->a)];
  const Pose& X_WB = X_WG_[static_cast<std::size_t>(pair->b)];
  const geometry::DistanceResult d = geometry::SignedDistance(*a.shape, X_WA, *b.shape, X_WB);
  std::optional<geometry::IntersectionVolume> volume;
  if (d.distance < 0.0)
    volume = geometry::IntersectConvex(a.polyhedron, X_WA, b.polyhedron, X_WB, d);
  if (!volume) {
    pair->anchor.active = false;
    return;
  }
  const PairForce force = ContactVolumeForce(*volume, Kinematics(a.body, V_WP),
                                             Kinematics(b.body, V_WP), gains_, &pair->anchor);
  ++stats_.contacts;
  const Vec3 origin = world_->body_state(pointer_).X_WB.p;
  for (const auto& [body, f] :
       {std::pair{a.body, force.f_W}, std::pair{b.body, Vec3(-force.f_W)}}) {
    if (body == pointer_) {
      pointer_wrench_.f += f;
      pointer_wrench_.tau += (force.p_W - origin).cross(f);
    } else if (Dynamic(world_->body(body))) {
      world_->AddForceAtPoint(body, f, force.p_W);
    }
  }
  if (a.body == pointer_ || b.body == pointer_) ++stats_.pointer_contacts;
}

void ContactVolumePhysics::Analyse(const Twist& V_WP) {
  stats_ = ContactVolumeStats{};
  pointer_wrench_ = Wrench{};
  for (std::size_t i = 0; i < pieces_.size(); ++i) X_WG_[i] = world_->geom_pose(pieces_[i].geom);
  for (Pair& pair : pairs_) {
    if (!Overlap(pair)) {
      pair.anchor.active = false;
      continue;
    }
    ++stats_.candidate_pairs;
    AnalysePair(&pair, V_WP);
  }
}

void ContactVolumePhysics::Publish(ir::PhysicsSnapshot* out) const {
  out->bodies.Clear();
  out->contacts.Clear();
  out->pairs.Clear();
  out->points.Clear();
  out->pointer_wrench_W = pointer_wrench_;
  out->pointer_contacts = stats_.pointer_contacts;
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

void ContactVolumePhysics::PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_, initial.X_WP);
  Publish(out);  // no force before the first step's analysis
  out->step = -1;
}

// The analysis sees the bodies at the start of the step and the pointer at the newest device
// pose; its forces act over the step (explicit penalty, as Springhead's PHPenaltyEngine).
void ContactVolumePhysics::PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_, report.X_WP);
  auto t0 = std::chrono::steady_clock::now();
  Analyse(report.V_WP);
  phases_.ir_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  world_->Step();
  phases_.world_step_ms = MsSince(t0);
  Publish(out);
}

}  // namespace mrh::physics::internal
