// SPDX-License-Identifier: Apache-2.0
// Physics side of 6-DOF rendering: neighbor search and the geometric IR (thesis §3.2.1).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "body_motions.h"
#include "material_table.h"
#include "mrh/geometry/broadphase.h"
#include "mrh/geometry/contact_region.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"
#include "mrh/ir/snapshot.h"
#include "mrh/settings/settings.h"
#include "normal_feature.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

using settings::RenderingSettings;

/// Work done by the last GeometricIrBuilder::Build, for experiments and benchmarks. Times are
/// wall-clock seconds of the physics thread.
struct GeometricIrStats {
  int candidates = 0;           ///< pointer-geom/object-geom pairs given to the narrow phase
  int neighbors = 0;            ///< pairs within neighbor_distance
  int penetrating = 0;          ///< pairs sent with penetration-region vertices
  int region_failures = 0;      ///< pairs whose region analysis failed (closest point sent)
  int dropped_pairs = 0;        ///< neighbors left out because a capacity was full
  std::int64_t sap_swaps = 0;   ///< endpoint swaps of the sweep and prune
  double broad_phase_s = 0.0;   ///< box updates + sweep and prune
  double narrow_phase_s = 0.0;  ///< signed distances of the candidates
  double region_s = 0.0;        ///< penetration regions + filling the snapshot
  double total_s = 0.0;
};

/// Builds the geometric IR of a pointer made of convex geoms (thesis §3.2.1): every geom of the
/// pointer body is a convex piece, and every piece/object-geom pair is its own IR pair.
///
/// Broad phase: world AABBs of all collidable geoms of the other bodies and of the pointer
/// pieces inflated by max(neighbor_margin, neighbor_distance), in an incremental sweep and
/// prune kept across Build calls (static geoms are boxed once). Narrow phase: signed distance
/// with witness points for each overlapping pair; a pair within neighbor_distance is a
/// neighbor. IR: plane (normal object → pointer, point on the object) and contact points
/// (penetration-region vertices below the plane, or the pointer's closest point as fallback)
/// in the pointer body frame. Neighbors are filled in order of increasing signed distance, so
/// on overflow the deepest pairs are kept. Physics thread only; not RT-safe.
class GeometricIrBuilder {
 public:
  /// Prepares a ConvexPolyhedron and a CollisionShape of every collidable geom not on the
  /// pointer body and of every geom of the pointer body.
  /// @throws mrh::SceneError if the pointer body has no geom, a pointer geom is a plane, or a
  /// geom cannot be represented (the message names the geom).
  GeometricIrBuilder(const world::World& world, int pointer_body,
                     const settings::RenderingSettings& rendering);

  /// Remembers every body's pose before a step (the interpolation start, BodyMotion::X_WB_prev).
  void CapturePreviousPoses(const world::World& world);

  /// Fills out->bodies, out->pairs and out->points for the pointer body at X_WP (world), from
  /// the world's current state. Clears those three first; ORs kStatusPairsFull,
  /// kStatusPointsFull, kStatusBodiesFull and kStatusRegionFallback into out->status.
  void Build(const world::World& world, const Pose& X_WP, ir::PhysicsSnapshot* out);

  const GeometricIrStats& stats() const { return stats_; }

  int num_pointer_pieces() const { return static_cast<int>(pointer_.size()); }

  int num_object_pieces() const { return static_cast<int>(objects_.size()); }

 private:
  /// A convex geom prepared for queries.
  struct Piece {
    int geom = -1;
    int body = -1;
    Pose X_BG;                     // geom in its body frame
    Pose X_WG;                     // last world pose (objects)
    bool moves = true;             // its body can move (boxes refreshed every Build)
    bool round = false;            // sphere or capsule (ir::GeometricPair::round)
    Faces faces = Faces::kCurved;  // NormalSide::faces
    int handle = -1;               // sweep-and-prune handle
    geometry::ConvexPolyhedron polyhedron;
    std::unique_ptr<geometry::CollisionShape> shape;
  };

  /// A pair within neighbor_distance, before the IR is filled.
  struct Neighbor {
    int pointer;  // index into pointer_
    int object;   // index into objects_
    geometry::DistanceResult d;
  };

  Piece MakePiece(const world::World& world, int geom) const;
  void UpdateBroadPhase(const world::World& world, const Pose& X_WP);
  void FindNeighbors();
  void FillPairs(const world::World& world, const Pose& X_WP, ir::PhysicsSnapshot* out);
  void FillPair(const Neighbor& n, const Pose& X_WP, int motion, ir::PhysicsSnapshot* out);
  void AddPointerPieces(const world::World& world);

  int pointer_body_;
  settings::RenderingSettings rendering_;
  double inflation_;  // pointer box margin (m)
  std::vector<Piece> pointer_;
  std::vector<Piece> objects_;
  std::vector<int> object_of_handle_;  // sweep-and-prune handle -> objects_ index, or -1
  geometry::SweepAndPrune sap_;
  BodyMotions motions_;
  MaterialTable materials_;
  std::vector<int> candidates_;      // scratch
  std::vector<Neighbor> neighbors_;  // scratch
  GeometricIrStats stats_;
};

}  // namespace mrh::physics::internal
