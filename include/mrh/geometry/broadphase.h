// SPDX-License-Identifier: Apache-2.0
// Axis-aligned bounding boxes of shapes and an incremental sweep-and-prune broad phase (thesis
// §3.2.1, after Cohen et al. 1995).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry {

/// The closed axis-aligned box [min, max] (m, world frame). A plane's box is unbounded (±inf).
/// RT-safe.
struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();

  /// True when every bound is finite.
  bool bounded() const noexcept { return IsFinite(min) && IsFinite(max); }

  /// True when the closed boxes share a point (touching boxes overlap).
  bool Overlaps(const Aabb& other) const noexcept {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }

  /// The box grown by `margin` (m, >= 0) on every side.
  Aabb Inflated(double margin) const noexcept {
    return Aabb{min - Vec3::Constant(margin), max + Vec3::Constant(margin)};
  }

  /// The box of all space.
  static Aabb Unbounded() noexcept;
};

/// World-frame bounding box of `shape` at pose X_WS: exact (the smallest axis-aligned box) for
/// every shape type: box and mesh from their vertices, sphere, capsule, cylinder and ellipsoid
/// in closed form; a plane gives Aabb::Unbounded(). @pre the shape is valid (a mesh has
/// vertices). RT-safe (a mesh costs O(vertices)).
Aabb ComputeAabb(const Shape& shape, const Pose& X_WS) noexcept;

/// Incremental sweep and prune (Cohen et al. 1995, I-COLLIDE) over a fixed set of boxes. The
/// three sorted endpoint lists and the set of overlapping pairs are kept between updates:
/// Update() restores the order by insertion sort, starting from the previous order, and every
/// swap of a min and a max endpoint adds or removes one pair. With coherent motion the work per
/// update is O(boxes + swaps), not a rebuild.
///
/// Unbounded boxes (planes) are kept out of the lists and overlap every box; overlaps() does not
/// list them, QueryOverlapping() always returns them. Handles are dense ints 0, 1, 2, ... in
/// order of Add(). Physics thread only; not RT-safe (pair lists grow as needed).
class SweepAndPrune {
 public:
  /// Adds a box and returns its handle. A box with an infinite bound is unbounded for good.
  /// The next Update() sorts from scratch. Not RT-safe.
  int Add(const Aabb& box);

  /// Moves a box; the lists and pairs catch up at the next Update(). Ignored for an unbounded
  /// handle. A non-finite box (a simulation blow-up) is parked far away, overlapping nothing.
  /// @pre 0 <= handle < size().
  void SetBox(int handle, const Aabb& box) noexcept;

  /// Re-sorts the endpoint lists and updates the overlapping pairs. Returns the endpoint swaps
  /// made (the work done; 0 when nothing moved past anything).
  std::int64_t Update();

  /// Bounded handles whose boxes overlap `handle`'s box, unordered, as of the last Update().
  std::span<const int> overlaps(int handle) const;

  /// Handles not in `group` whose box overlaps at least one box of `group`, plus every
  /// unbounded handle not in `group`, ascending and without repeats, as of the last Update().
  /// `out` is cleared first. An unbounded handle in `group` overlaps every box.
  void QueryOverlapping(std::span<const int> group, std::vector<int>* out) const;

  int size() const { return static_cast<int>(boxes_.size()); }

  const Aabb& box(int handle) const { return boxes_[static_cast<std::size_t>(handle)]; }

  bool unbounded(int handle) const { return unbounded_[static_cast<std::size_t>(handle)]; }

  /// Overlapping pairs of bounded boxes, as of the last Update().
  std::int64_t num_pairs() const { return num_pairs_; }

 private:
  struct Endpoint {
    double value;
    int handle;
    bool is_max;
  };

  void Rebuild();
  std::int64_t SortAxis(int axis);
  void AddPair(int a, int b);
  void RemovePair(int a, int b);
  bool HasPair(int a, int b) const;

  std::vector<Aabb> boxes_;
  std::vector<bool> unbounded_;
  std::vector<int> unbounded_handles_;
  std::vector<Endpoint> axes_[3];
  // Per handle and axis: index of its min endpoint (2 * axis) and max endpoint (2 * axis + 1).
  std::vector<std::array<int, 6>> slots_;
  std::vector<std::vector<int>> overlaps_;
  std::int64_t num_pairs_ = 0;
  bool needs_rebuild_ = true;
};

}  // namespace mrh::geometry
