// SPDX-License-Identifier: Apache-2.0
// Haptic-side interpolation of the geometric IR between physics steps (thesis §3.2.2, which
// interpolates the planes and contact points but gives no formulas).
#pragma once

#include <array>
#include <cstdint>

#include "mrh/ir/snapshot.h"
#include "mrh/render/tick_ir.h"

namespace mrh::render {

/// Keeps the current and previous geometric IR and, every tick, produces the TickIr for the
/// current pointer pose: normal blended from the pair's previous normal to the new one
/// (normalized lerp), object pose blended from X_WB_prev to X_WB (lerp + slerp), contact points
/// re-posed with the current pointer pose. A pair new in this snapshot uses its new values for
/// "previous". Haptic thread only; RT-safe (no allocation after construction).
class IrInterpolator {
 public:
  /// A new snapshot becomes current; the normals rendered at the last tick become the
  /// "previous" normals of the pairs that persist (matched by geom ids). RT-safe.
  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept;

  /// Fills `out` for interpolation parameter alpha in [0, 1] (clamped; NaN counts as 1) and
  /// pointer pose X_WP (world). A non-finite X_WP gives an empty `out`. RT-safe.
  void Evaluate(double alpha, const Pose& X_WP, TickIr* out) noexcept;

  /// The adopted snapshot.
  const ir::PhysicsSnapshot& snapshot() const noexcept { return snapshot_; }

 private:
  ir::PhysicsSnapshot snapshot_;
  std::array<Vec3, ir::kMaxGeometricPairs> previous_n_{};
  std::array<Vec3, ir::kMaxGeometricPairs> rendered_n_{};
  std::array<std::uint64_t, ir::kMaxGeometricPairs> rendered_key_{};
  std::array<bool, ir::kMaxGeometricPairs> new_pair_{};
  std::size_t rendered_count_ = 0;
};

/// Key of a pair: (pointer geom, object geom). RT-safe.
inline std::uint64_t PairKey(int pointer_geom, int object_geom) noexcept {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(pointer_geom)) << 32) |
         static_cast<std::uint32_t>(object_geom);
}

/// The normal blend from `previous` to `next` at alpha in [0, 1], unit. Where the
/// two nearly cancel (a normal that flipped, alpha near 1/2) the blend has no reliable direction
/// and `next` is returned. RT-safe.
Vec3 BlendNormal(const Vec3& previous, const Vec3& next, double alpha) noexcept;

}  // namespace mrh::render
