// SPDX-License-Identifier: Apache-2.0
// Which body's surface a geometric pair's contact normal belongs to.
#pragma once

#include <cstdint>
#include <span>

#include "mrh/core/spatial.h"
#include "mrh/geometry/polyhedron.h"
#include "mrh/ir/snapshot.h"

namespace mrh::physics::internal {

/// What a side's polyhedron faces are: the body's own faces (a box or a mesh), facets of a
/// surface that turning about its axis leaves in place (a cylinder's side), or facets of another
/// curved surface (sphere, capsule, ellipsoid), which name no feature of the body.
enum class Faces : std::uint8_t { kFlat, kAxial, kCurved };

/// A side of a geometric pair, for NormalFeature: its polyhedron at its world pose and what its
/// faces are.
struct NormalSide {
  const geometry::ConvexPolyhedron* polyhedron = nullptr;
  Pose X_WG;
  Faces faces = Faces::kCurved;
};

/// The body a contact normal belongs to and the normal as that body carries it.
struct NormalOwner {
  ir::NormalFrame frame = ir::NormalFrame::kObject;
  Vec3 n_W = Vec3::UnitZ();  ///< unit, object → pointer (world)
};

/// Classifies the contact normal n_W (object → pointer) of a pointer–object pair by the face
/// normal nearest it on either side, as a contact's features are classified. With a flat
/// pointer (a box or a mesh):
///  - the object's face when one of a flat object's faces is at least as near n_W as any of the
///    pointer's, or when every contact point (points_W: the penetration region's vertices, in
///    the object; none outside a penetration) leaves the object along n_W through that face: the
///    points lie under it, not by an edge. The normal is then that face's own: a face–face contact,
///    whose minimal penetration direction switches between the two nearly parallel faces as they
///    tilt, is rendered on the object's face at every relative tilt;
///  - the pointer's face when one of its faces is nearer than any of the object's (an object
///    edge or vertex on a pointer face), or as near as any of a cylinder's facets (its side on a
///    pointer face): n_W as given, carried by the pointer;
///  - otherwise (a pointer edge on a curved object, an ellipsoid, an edge on an edge): n_W as
///    given, carried by the object (an ellipsoid's tangent plane turns with it as it rocks).
/// A curved pointer's facets name no feature: n_W as given, carried by the object.
/// Not RT-safe (physics thread).
NormalOwner NormalFeature(const NormalSide& pointer, const NormalSide& object, const Vec3& n_W,
                          std::span<const Vec3> points_W);

}  // namespace mrh::physics::internal
