// SPDX-License-Identifier: Apache-2.0
// Haptic-side interpolation of the geometric IR between physics steps (thesis §3.2.2, which
// interpolates the planes and contact points but gives no formulas).
#include "mrh/render/ir_interpolator.h"

#include <algorithm>
#include <cmath>

namespace mrh::render {
namespace {

// A blended normal shorter than this (previous and new nearly opposite, alpha near 1/2) has no
// reliable direction; the new normal is used instead.
constexpr double kMinBlendedNormal = 1e-9;

std::uint64_t KeyOf(const ir::GeometricPair& pair) noexcept {
  return PairKey(pair.pointer_geom, pair.object_geom);
}

// Points are fixed on the pointer: re-posed with this tick's pointer pose, never blended.
// depth = n·(c − v) = n·c − n·v.
void AppendPoints(const ir::PhysicsSnapshot& snapshot, const ir::GeometricPair& pair,
                  const TickPair& tick, int index, const Mat3& R_WP, const Vec3& p_WP,
                  TickIr* out) noexcept {
  const double n_dot_c = tick.n_W.dot(tick.c_W);
  for (int k = pair.first_point; k < pair.first_point + pair.num_points; ++k) {
    if (k < 0 || static_cast<std::size_t>(k) >= snapshot.points.size()) break;
    const ir::PairPoint& point = snapshot.points[static_cast<std::size_t>(k)];
    TickPoint p;
    p.p_PV = point.p_PV;
    p.v_W = R_WP * point.p_PV + p_WP;
    p.depth = n_dot_c - tick.n_W.dot(p.v_W);
    p.pair = index;
    if (!out->points.PushBack(p)) break;
  }
}

}  // namespace

Vec3 BlendNormal(const Vec3& previous, const Vec3& next, double alpha) noexcept {
  const Vec3 n = (1.0 - alpha) * previous + alpha * next;
  const double length = n.norm();
  if (!(length > kMinBlendedNormal)) return next;
  return n / length;
}

// Each persisting pair starts its blend from the normal it was last rendered with, so the
// normal is continuous across the snapshot switch; a new pair has no history and starts at its
// new normal.
void IrInterpolator::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  for (std::size_t i = 0; i < snapshot.pairs.size(); ++i) {
    const ir::GeometricPair& pair = snapshot.pairs[i];
    const std::uint64_t key = KeyOf(pair);
    previous_n_[i] = pair.n_W;
    new_pair_[i] = true;
    for (std::size_t o = 0; o < rendered_count_; ++o) {
      if (rendered_key_[o] == key) {
        previous_n_[i] = rendered_n_[o];
        new_pair_[i] = false;
        break;
      }
    }
  }
  snapshot_ = snapshot;
  rendered_count_ = snapshot_.pairs.size();
  for (std::size_t i = 0; i < rendered_count_; ++i) {
    rendered_key_[i] = KeyOf(snapshot_.pairs[i]);
    rendered_n_[i] = previous_n_[i];
  }
}

void IrInterpolator::Evaluate(double alpha, const Pose& X_WP, TickIr* out) noexcept {
  out->pairs.Clear();
  out->points.Clear();
  if (!IsFinite(X_WP)) return;
  const double a = std::isnan(alpha) ? 1.0 : std::clamp(alpha, 0.0, 1.0);
  // One matrix for all points (X_WP * p with the quaternion costs twice the flops per point).
  const Mat3 R_WP = X_WP.q.toRotationMatrix();
  for (std::size_t i = 0; i < snapshot_.pairs.size(); ++i) {
    const ir::GeometricPair& pair = snapshot_.pairs[i];
    if (pair.motion < 0 || static_cast<std::size_t>(pair.motion) >= snapshot_.bodies.size()) {
      continue;
    }
    const ir::BodyMotion& body = snapshot_.bodies[static_cast<std::size_t>(pair.motion)];
    TickPair tick;
    tick.key = rendered_key_[i];
    tick.body = body.body;
    tick.motion = pair.motion;
    tick.is_static = body.is_static;
    tick.X_WB = Interpolate(body.X_WB_prev, body.X_WB, a);
    tick.p_WCm = tick.X_WB * body.p_BCm;
    tick.n_W = BlendNormal(previous_n_[i], pair.n_W, a);
    tick.p_BC = pair.p_BC;
    tick.c_W = tick.X_WB * pair.p_BC;
    tick.first = static_cast<int>(out->points.size());
    tick.new_pair = new_pair_[i];
    tick.V_WCm = body.V_WCm;
    tick.object_geom = pair.object_geom;
    tick.material = pair.material;
    rendered_n_[i] = tick.n_W;
    AppendPoints(snapshot_, pair, tick, static_cast<int>(out->pairs.size()), R_WP, X_WP.p, out);
    tick.count = static_cast<int>(out->points.size()) - tick.first;
    (void)out->pairs.PushBack(tick);
  }
}

}  // namespace mrh::render
