// SPDX-License-Identifier: Apache-2.0
// Contact-normal classification of a geometric pair by its nearest face normal.
#include "normal_feature.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrh::physics::internal {
namespace {

struct NearestFace {
  double alignment = -2.0;  // cosine between the face's outward normal and the direction
  Vec3 a_W = Vec3::UnitZ();
};

// The face of `side` whose outward normal (world) is nearest the direction d_W.
NearestFace Nearest(const NormalSide& side, const Vec3& d_W) {
  NearestFace best;
  if (side.polyhedron == nullptr) return best;
  const Vec3 d_G = side.X_WG.q.conjugate() * d_W;
  for (const geometry::Halfspace& h : side.polyhedron->faces()) {
    const double alignment = h.a.dot(d_G);
    if (alignment > best.alignment) {
      best.alignment = alignment;
      best.a_W = side.X_WG.q * h.a;
    }
  }
  return best;
}

// Whether every point, moved along d_W out of the object it lies in, leaves it through face
// `face` (world normal a_W) rather than through another face turned toward d_W: the points then
// lie under that face, not by an edge or a vertex between faces the contact could rest on (a
// box's vertical edge, its faces 45° either side of d_W; a hexagonal prism's, 30°). A face
// turned more than 60° from d_W is a side of the patch (the seam of a compound body, on which
// region vertices lie), not one it could rest on. A point that leaves through another
// face within kTie of this one lies on their edge and leaves through both.
bool LeaveThrough(const NormalSide& side, const Vec3& a_W, std::span<const Vec3> points_W,
                  const Vec3& d_W) {
  constexpr double kTie = 1e-9;    // m
  constexpr double kFacing = 0.5;  // cos 60°
  if (points_W.empty()) return false;
  const Vec3 d_G = side.X_WG.q.conjugate() * d_W;
  const Vec3 a_G = side.X_WG.q.conjugate() * a_W;
  const Pose X_GW = side.X_WG.Inverse();
  for (const Vec3& p_W : points_W) {
    const Vec3 p_G = X_GW * p_W;
    double through_face = std::numeric_limits<double>::infinity();
    double through_other = std::numeric_limits<double>::infinity();
    for (const geometry::Halfspace& h : side.polyhedron->faces()) {
      const double rate = h.a.dot(d_G);
      if (!(rate > 0.0)) continue;
      const double t = (h.b - h.a.dot(p_G)) / rate;
      if ((h.a - a_G).squaredNorm() < 1e-18) {
        through_face = t;
      } else if (rate >= kFacing) {
        through_other = std::min(through_other, t);
      }
    }
    if (!(through_face <= through_other + kTie)) return false;
  }
  return true;
}

}  // namespace

NormalOwner NormalFeature(const NormalSide& pointer, const NormalSide& object, const Vec3& n_W,
                          std::span<const Vec3> points_W) {
  // The object's outward normal at the contact is n_W; the pointer's is −n_W.
  const NearestFace on_object = Nearest(object, n_W);
  const NearestFace on_pointer = Nearest(pointer, -n_W);
  NormalOwner owner;
  owner.n_W = n_W;
  // A curved pointer meets every direction with a facet: its faces name no feature.
  if (pointer.faces != Faces::kFlat) return owner;
  const bool object_flat = object.faces == Faces::kFlat;
  if (object_flat && (on_object.alignment >= on_pointer.alignment ||
                      LeaveThrough(object, on_object.a_W, points_W, n_W))) {
    owner.n_W = on_object.a_W.normalized();
  } else if (object_flat ||
             (object.faces == Faces::kAxial && on_pointer.alignment >= on_object.alignment)) {
    owner.frame = ir::NormalFrame::kPointer;
  }
  return owner;
}

}  // namespace mrh::physics::internal
