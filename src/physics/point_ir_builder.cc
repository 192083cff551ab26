// SPDX-License-Identifier: Apache-2.0
// Neighbor search and Adachi plane IR for a sphere pointer (physics thread).
#include "point_ir_builder.h"

#include <cmath>

#include "mrh/world/world.h"

namespace mrh::physics::internal {
namespace {

// Below this the witness vector is too short to define a direction (m).
constexpr double kMinDirectionLength = 1e-12;

geometry::Shape PointerSphere(double radius) {
  geometry::Shape s;
  s.type = geometry::ShapeType::kSphere;
  s.size = Vec3(radius, 0, 0);
  return s;
}

// Unit normal from the object toward the pointer (thesis §4.2.1: Adachi's plane + point IR).
// While the sphere's centre is outside
// the object (depth < radius) the object's witness is its closest point to the centre, so
// centre − witness is well conditioned; deeper, the EPA witness pair gives the separating
// direction.
Vec3 ContactNormal(const geometry::DistanceResult& r, const Vec3& centre, double radius) {
  Vec3 dir;
  if (r.distance > -radius) {
    dir = centre - r.p_WB;
  } else {
    dir = r.p_WB - r.p_WA;
  }
  const double len = dir.norm();
  if (len < kMinDirectionLength) return Vec3::UnitZ();
  return dir / len;
}

// The core segment of a sphere or capsule geom, in its body frame (MJCF: a capsule's axis is
// the geom's z, half-length size[1]).
void SetRoundCore(const world::GeomInfo& info, ir::PointContact* contact) {
  const geometry::Shape& s = info.shape;
  if (s.type != geometry::ShapeType::kSphere && s.type != geometry::ShapeType::kCapsule) return;
  const double h = s.type == geometry::ShapeType::kCapsule ? s.size.y() : 0.0;
  contact->r = s.size.x();
  contact->core_B = {info.X_BG * Vec3(0.0, 0.0, -h), info.X_BG * Vec3(0.0, 0.0, h)};
}

}  // namespace

PointIrBuilder::PointIrBuilder(const world::World& world, int pointer_body, double radius,
                               const settings::RenderingSettings& rendering)
    : pointer_body_(pointer_body),
      radius_(radius),
      rendering_(rendering),
      materials_(world, rendering),
      pointer_shape_(PointerSphere(radius)),
      motions_(world) {
  for (int g = 0; g < world.num_geoms(); ++g) {
    const world::GeomInfo& info = world.geom(g);
    if (info.body == pointer_body_ || !info.collides) continue;
    candidates_.push_back(
        Candidate{g, geometry::CollisionShape(info.shape), info.shape.BoundingRadius()});
  }
}

void PointIrBuilder::CapturePreviousPoses(const world::World& world) {
  motions_.CapturePreviousPoses(world);
}

void PointIrBuilder::Build(const world::World& world, const Pose& X_WP,
                           ir::PhysicsSnapshot* out) const {
  out->bodies.Clear();
  out->contacts.Clear();
  const Pose X_WS{X_WP.p, Quat::Identity()};
  const double reach = radius_ + rendering_.neighbor_margin;
  for (const Candidate& c : candidates_) {
    const Pose X_WG = world.geom_pose(c.geom);
    // Broad phase: bounding spheres (planes are unbounded and always pass).
    if ((X_WG.p - X_WP.p).norm() > c.bounding_radius + reach) continue;
    const geometry::DistanceResult r =
        geometry::SignedDistance(pointer_shape_, X_WS, c.shape, X_WG);
    if (r.distance > rendering_.neighbor_distance) continue;
    if (out->contacts.full()) {
      out->status |= ir::kStatusContactsFull;
      continue;
    }
    const int body = world.geom(c.geom).body;
    const int motion = motions_.Add(world, body, out);
    if (motion < 0) continue;
    const Pose& X_WB = out->bodies[static_cast<std::size_t>(motion)].X_WB;
    ir::PointContact contact;
    contact.motion = motion;
    contact.geom = c.geom;
    contact.p_BC = X_WB.Inverse() * r.p_WB;
    contact.n_W = ContactNormal(r, X_WP.p, radius_);
    contact.distance = r.distance;
    SetRoundCore(world.geom(c.geom), &contact);
    contact.material = materials_.of(c.geom);
    (void)out->contacts.PushBack(contact);
  }
}

}  // namespace mrh::physics::internal
