// SPDX-License-Identifier: Apache-2.0
// Neighbor search (sweep and prune + signed distance) and geometric IR construction.
#include "geometric_ir_builder.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <tuple>

#include "mrh/core/error.h"
#include "mrh/world/world.h"

namespace mrh::physics::internal {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

std::string GeomLabel(const world::World& world, int geom) {
  const world::GeomInfo& info = world.geom(geom);
  const std::string& body = world.body(info.body).name;
  const std::string name = info.name.empty() ? fmt::format("geom {}", geom)
                                             : fmt::format("geom '{}' (id {})", info.name, geom);
  return body.empty() ? name : fmt::format("{} of body '{}'", name, body);
}

// A body whose pose can change between builds: free or jointed, or mocap (moved by the user).
bool BodyMoves(const world::BodyInfo& body) {
  return body.is_mocap || !body.is_static;
}

// The region's points into out->points in the pointer frame (status kStatusPointsFull when
// they do not fit).
void PushPoints(const geometry::ContactRegion& region, const Pose& X_WP, ir::PhysicsSnapshot* out) {
  const Pose X_PW = X_WP.Inverse();
  for (std::size_t k = 0; k < region.points_W.size(); ++k) {
    if (!out->points.PushBack(ir::PairPoint{X_PW * region.points_W[k], region.depths[k]})) {
      out->status |= ir::kStatusPointsFull;
      break;
    }
  }
}

}  // namespace

GeometricIrBuilder::GeometricIrBuilder(const world::World& world, int pointer_body,
                                       const settings::RenderingSettings& rendering)
    : pointer_body_(pointer_body),
      rendering_(rendering),
      // Below neighbor_distance the broad phase could drop a true neighbor (an AABB gap never
      // exceeds the distance between the shapes), so the margin never goes below it.
      inflation_(std::max(rendering.neighbor_margin, rendering.neighbor_distance)),
      motions_(world),
      materials_(world, rendering) {
  AddPointerPieces(world);
  for (int g = 0; g < world.num_geoms(); ++g) {
    const world::GeomInfo& info = world.geom(g);
    if (info.body == pointer_body_ || !info.collides) continue;
    objects_.push_back(MakePiece(world, g));
  }
  // Static geoms are boxed here once; moving ones and the pointer at every Build.
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    Piece& o = objects_[i];
    o.X_WG = world.geom_pose(o.geom);
    o.handle = sap_.Add(geometry::ComputeAabb(o.shape->shape(), o.X_WG));
    object_of_handle_.push_back(static_cast<int>(i));
  }
  for (Piece& p : pointer_) {
    p.handle = sap_.Add(geometry::Aabb{});
    object_of_handle_.push_back(-1);
  }
}

// The pointer body's geoms as pieces; throws SceneError for a plane or no geom.
void GeometricIrBuilder::AddPointerPieces(const world::World& world) {
  const world::BodyInfo& pointer = world.body(pointer_body_);
  for (const int g : pointer.geoms) {
    if (world.geom(g).shape.type == geometry::ShapeType::kPlane) {
      throw SceneError(fmt::format(
          "pointer {} is a plane; expected bounded convex geoms (box, mesh, sphere, capsule, "
          "cylinder, ellipsoid): replace it",
          GeomLabel(world, g)));
    }
    pointer_.push_back(MakePiece(world, g));
  }
  if (pointer_.empty()) {
    throw SceneError(fmt::format(
        "pointer body '{}' has no geom; expected at least one convex geom (box, mesh, sphere, "
        "capsule, cylinder, ellipsoid) for 6-DOF rendering: add one to the body",
        pointer.name));
  }
}

GeometricIrBuilder::Piece GeometricIrBuilder::MakePiece(const world::World& world, int geom) const {
  const world::GeomInfo& info = world.geom(geom);
  Piece piece;
  piece.geom = geom;
  piece.body = info.body;
  piece.X_BG = info.X_BG;
  piece.moves = BodyMoves(world.body(info.body));
  piece.round = info.shape.type == geometry::ShapeType::kSphere ||
                info.shape.type == geometry::ShapeType::kCapsule;
  piece.faces =
      info.shape.type == geometry::ShapeType::kBox || info.shape.type == geometry::ShapeType::kMesh
          ? Faces::kFlat
      : info.shape.type == geometry::ShapeType::kCylinder ? Faces::kAxial
                                                          : Faces::kCurved;
  try {
    piece.polyhedron =
        geometry::ConvexPolyhedron::FromShape(info.shape, rendering_.curved_segments);
    piece.shape = std::make_unique<geometry::CollisionShape>(info.shape);
  } catch (const Error& e) {
    throw SceneError(fmt::format("{}: {}", GeomLabel(world, geom), e.what()));
  }
  return piece;
}

void GeometricIrBuilder::CapturePreviousPoses(const world::World& world) {
  motions_.CapturePreviousPoses(world);
}

void GeometricIrBuilder::Build(const world::World& world, const Pose& X_WP,
                               ir::PhysicsSnapshot* out) {
  const Clock::time_point start = Clock::now();
  stats_ = GeometricIrStats{};
  out->bodies.Clear();
  out->pairs.Clear();
  out->points.Clear();
  if (!IsFinite(X_WP)) return;
  UpdateBroadPhase(world, X_WP);
  const Clock::time_point broad = Clock::now();
  FindNeighbors();
  const Clock::time_point narrow = Clock::now();
  FillPairs(world, X_WP, out);
  const Clock::time_point end = Clock::now();
  stats_.broad_phase_s = Seconds(start, broad);
  stats_.narrow_phase_s = Seconds(broad, narrow);
  stats_.region_s = Seconds(narrow, end);
  stats_.total_s = Seconds(start, end);
}

void GeometricIrBuilder::UpdateBroadPhase(const world::World& world, const Pose& X_WP) {
  for (Piece& o : objects_) {
    if (!o.moves) continue;
    o.X_WG = world.geom_pose(o.geom);
    sap_.SetBox(o.handle, geometry::ComputeAabb(o.shape->shape(), o.X_WG));
  }
  for (Piece& p : pointer_) {
    p.X_WG = X_WP * p.X_BG;
    sap_.SetBox(p.handle, geometry::ComputeAabb(p.shape->shape(), p.X_WG).Inflated(inflation_));
  }
  stats_.sap_swaps = sap_.Update();
}

// Candidates are queried per pointer piece, so a piece is measured only against the objects its
// own inflated box reaches.
void GeometricIrBuilder::FindNeighbors() {
  neighbors_.clear();
  for (std::size_t i = 0; i < pointer_.size(); ++i) {
    const Piece& p = pointer_[i];
    sap_.QueryOverlapping(std::span<const int>(&p.handle, 1), &candidates_);
    for (const int handle : candidates_) {
      const int o = object_of_handle_[static_cast<std::size_t>(handle)];
      if (o < 0) continue;
      ++stats_.candidates;
      const Piece& object = objects_[static_cast<std::size_t>(o)];
      const geometry::DistanceResult d =
          geometry::SignedDistance(*p.shape, p.X_WG, *object.shape, object.X_WG);
      if (d.distance <= rendering_.neighbor_distance) {
        neighbors_.push_back(Neighbor{static_cast<int>(i), o, d});
      }
    }
  }
  stats_.neighbors = static_cast<int>(neighbors_.size());
  // Deepest first, so that a full snapshot keeps the pairs that push hardest; ties by geom ids
  // keep the order deterministic.
  std::sort(neighbors_.begin(), neighbors_.end(), [this](const Neighbor& a, const Neighbor& b) {
    return std::make_tuple(a.d.distance, pointer_[static_cast<std::size_t>(a.pointer)].geom,
                           objects_[static_cast<std::size_t>(a.object)].geom) <
           std::make_tuple(b.d.distance, pointer_[static_cast<std::size_t>(b.pointer)].geom,
                           objects_[static_cast<std::size_t>(b.object)].geom);
  });
}

void GeometricIrBuilder::FillPairs(const world::World& world, const Pose& X_WP,
                                   ir::PhysicsSnapshot* out) {
  for (const Neighbor& n : neighbors_) {
    if (out->pairs.full()) {
      out->status |= ir::kStatusPairsFull;
      ++stats_.dropped_pairs;
      continue;
    }
    const int motion = motions_.Add(world, objects_[static_cast<std::size_t>(n.object)].body, out);
    if (motion < 0) {
      ++stats_.dropped_pairs;
      continue;
    }
    FillPair(n, X_WP, motion, out);
  }
}

void GeometricIrBuilder::FillPair(const Neighbor& n, const Pose& X_WP, int motion,
                                  ir::PhysicsSnapshot* out) {
  const Piece& p = pointer_[static_cast<std::size_t>(n.pointer)];
  const Piece& o = objects_[static_cast<std::size_t>(n.object)];
  const geometry::ContactRegion region =
      geometry::ComputeContactRegion(p.polyhedron, p.X_WG, o.polyhedron, o.X_WG, n.d);
  if (region.status == geometry::RegionStatus::kFailed) {
    out->status |= ir::kStatusRegionFallback;
    ++stats_.region_failures;
  }
  ir::GeometricPair pair;
  pair.motion = motion;
  pair.object_geom = o.geom;
  pair.pointer_geom = p.geom;
  pair.n_W = region.n_W;
  pair.p_BC = out->bodies[static_cast<std::size_t>(motion)].X_WB.Inverse() * region.c_W;
  pair.first_point = static_cast<int>(out->points.size());
  pair.distance = n.d.distance;
  pair.penetrating = region.status == geometry::RegionStatus::kRegion;
  pair.round = o.round;
  pair.material = materials_.of(o.geom);
  const NormalOwner owner = NormalFeature(NormalSide{&p.polyhedron, p.X_WG, p.faces},
                                          NormalSide{&o.polyhedron, o.X_WG, o.faces}, region.n_W,
                                          region.status == geometry::RegionStatus::kRegion
                                              ? std::span<const Vec3>(region.points_W)
                                              : std::span<const Vec3>());
  pair.normal_frame = owner.frame;
  pair.n_F =
      owner.frame == ir::NormalFrame::kPointer
          ? Vec3(X_WP.q.conjugate() * owner.n_W)
          : Vec3(out->bodies[static_cast<std::size_t>(motion)].X_WB.q.conjugate() * owner.n_W);
  if (pair.penetrating) ++stats_.penetrating;
  PushPoints(region, X_WP, out);
  pair.num_points = static_cast<int>(out->points.size()) - pair.first_point;
  (void)out->pairs.PushBack(pair);
}

}  // namespace mrh::physics::internal
