// SPDX-License-Identifier: Apache-2.0
// Tests of the B5 per-contact penalty sum (Berkelman & Hollis 2000): stiffness that grows with the
// contact count, the tilted-box wrench, damping, reactions and bad input.
#include "mrh/render/penalty_sum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mrh/core/error.h"
#include "support/alloc_guard.h"

namespace mrh::render {
namespace {

constexpr double kK = 9000.0;    // N/m (T3.1's k_t)
constexpr double kHalf = 0.1;    // half side of the 0.2 m cube pointer (m)
constexpr double kDepth = 1e-3;  // m
constexpr double kDt = 1e-3;     // s

std::vector<Vec3> CubeCorners() {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1 ? 1 : -1) * kHalf, (i & 2 ? 1 : -1) * kHalf,
                         (i & 4 ? 1 : -1) * kHalf);
  }
  return corners;
}

// One pair: the floor z = 0 (normal +z, object body `body`, COM at p_WCm) and the cube's corners
// re-posed with X_WP, depth = n·(c − v) as IrInterpolator::Evaluate computes it.
TickIr FloorIr(const Pose& X_WP, bool is_static = true, const Vec3& p_WCm = Vec3::Zero()) {
  TickIr ir;
  TickPair pair;
  pair.key = 7;
  pair.body = 3;
  pair.is_static = is_static;
  pair.p_WCm = p_WCm;
  pair.n_W = Vec3::UnitZ();
  pair.c_W = Vec3::Zero();
  pair.first = 0;
  for (const Vec3& p_PV : CubeCorners()) {
    const Vec3 v_W = X_WP * p_PV;
    (void)ir.points.PushBack(TickPoint{p_PV, v_W, pair.n_W.dot(pair.c_W - v_W), 0});
  }
  pair.count = static_cast<int>(ir.points.size());
  (void)ir.pairs.PushBack(pair);
  return ir;
}

TEST(PenaltySum, FourCoplanarContactsGiveFourTimesTheSpringAndNoTorque) {
  const Pose X_WP{Vec3(0.3, -0.2, kHalf - kDepth), Quat::Identity()};
  const TickIr ir = FloorIr(X_WP);
  PenaltySumRenderer renderer({.k = kK, .d = 0.0});
  PenaltySumOutput out;
  renderer.Tick(ir, X_WP, kDt, &out);
  EXPECT_EQ(out.contacts, 4);
  // 4 k δ: four times what the proxy renders for the same face (k_t δ, by eq. 3.2–3.5).
  EXPECT_NEAR(out.w_W.f.z(), 4.0 * kK * kDepth, 1e-9);
  EXPECT_NEAR(out.w_W.f.head<2>().norm(), 0.0, 1e-12);
  EXPECT_NEAR(out.w_W.tau.norm(), 0.0, 1e-12);
  const Wrench pure = PenaltySumWrench(ir, X_WP, kK);
  EXPECT_NEAR((pure.f - out.w_W.f).norm(), 0.0, 1e-12);
}

TEST(PenaltySum, EdgeContactGivesTwiceTheSpring) {
  // The cube turned 45° about x rests on an edge: two corners at depth δ.
  const Quat q(Eigen::AngleAxisd(M_PI / 4.0, Vec3::UnitX()));
  const Pose X_WP{Vec3(0.0, 0.0, kHalf * std::sqrt(2.0) - kDepth), q};
  PenaltySumOutput out;
  PenaltySumRenderer renderer({.k = kK, .d = 0.0});
  renderer.Tick(FloorIr(X_WP), X_WP, kDt, &out);
  EXPECT_EQ(out.contacts, 2);
  EXPECT_NEAR(out.w_W.f.z(), 2.0 * kK * kDepth, 1e-9);
  EXPECT_NEAR(out.w_W.tau.norm(), 0.0, 1e-12);
}

TEST(PenaltySum, TiltedBoxSumsIndependentSpringsAndMoments) {
  const Quat q = Quat(Eigen::AngleAxisd(0.3, Vec3(1.0, 2.0, 0.5).normalized())).normalized();
  const Pose X_WP{Vec3(0.05, 0.02, 0.09), q};
  const Mat3 R = q.toRotationMatrix();
  // Expected answer from the corners alone: depth of corner i below z = 0 is −(x + R pᵢ)_z.
  Vec3 f = Vec3::Zero();
  Vec3 tau = Vec3::Zero();
  int penetrating = 0;
  for (const Vec3& p : CubeCorners()) {
    const Vec3 r = R * p;
    const double depth = -(X_WP.p.z() + r.z());
    if (depth <= 0.0) continue;
    ++penetrating;
    f += kK * depth * Vec3::UnitZ();
    tau += r.cross(kK * depth * Vec3::UnitZ());
  }
  ASSERT_GE(penetrating, 2);  // the pose really is a multi-contact, asymmetric one
  ASSERT_GT(tau.norm(), 1e-3);
  PenaltySumRenderer renderer({.k = kK, .d = 0.0});
  PenaltySumOutput out;
  renderer.Tick(FloorIr(X_WP), X_WP, kDt, &out);
  EXPECT_EQ(out.contacts, penetrating);
  EXPECT_NEAR((out.w_W.f - f).norm(), 0.0, 1e-9 * f.norm());
  EXPECT_NEAR((out.w_W.tau - tau).norm(), 0.0, 1e-9 * tau.norm());
}

TEST(PenaltySum, DampingActsOnTheDepthRateOfAContinuingContact) {
  constexpr double kD = 20.0;
  constexpr double kSpeed = 0.05;  // m/s into the floor
  PenaltySumRenderer renderer({.k = kK, .d = kD});
  PenaltySumOutput out;
  Pose X_WP{Vec3(0.0, 0.0, kHalf - kDepth), Quat::Identity()};
  renderer.Tick(FloorIr(X_WP), X_WP, kDt, &out);
  EXPECT_NEAR(out.w_W.f.z(), 4.0 * kK * kDepth, 1e-9);  // first tick of a contact: no rate
  X_WP.p.z() -= kSpeed * kDt;
  renderer.Tick(FloorIr(X_WP), X_WP, kDt, &out);
  EXPECT_NEAR(out.w_W.f.z(), 4.0 * (kK * (kDepth + kSpeed * kDt) + kD * kSpeed), 1e-6);
  // Pulling out fast: the damper may not pull the hand into the floor.
  X_WP.p.z() += 10.0 * kDepth * 0.1;
  renderer.Tick(FloorIr(X_WP), X_WP, kDt, &out);
  EXPECT_GE(out.w_W.f.z(), 0.0);
}

TEST(PenaltySum, ReactionOnAMovingObjectIsMinusTheForceAboutItsCom) {
  const Quat q(Eigen::AngleAxisd(0.2, Vec3::UnitY()));
  const Pose X_WP{Vec3(0.0, 0.0, 0.11), q};
  const Vec3 p_WCm(0.4, -0.1, -0.05);
  const TickIr ir = FloorIr(X_WP, /*is_static=*/false, p_WCm);
  PenaltySumRenderer renderer({.k = kK, .d = 0.0});
  PenaltySumOutput out;
  renderer.Tick(ir, X_WP, kDt, &out);
  ASSERT_EQ(out.reactions.size(), 1u);
  const Wrench& r = out.reactions[0].w_W;
  EXPECT_NEAR((r.f + out.w_W.f).norm(), 0.0, 1e-12);
  // The moment about the COM equals the pointer torque moved from the pointer origin to the
  // COM, negated: −(τ + (x_P − c) × f).
  const Vec3 expected = -(out.w_W.tau + (X_WP.p - p_WCm).cross(out.w_W.f));
  EXPECT_NEAR((r.tau - expected).norm(), 0.0, 1e-9);
  ir::HapticReport report;
  AddReactionImpulses(out.reactions, kDt, &report);
  ASSERT_EQ(report.impulses.size(), 1u);
  EXPECT_NEAR((report.impulses[0].linear - r.f * kDt).norm(), 0.0, 1e-15);
}

TEST(PenaltySum, StaticObjectTakesNoReactionAndNoContactGivesZero) {
  PenaltySumRenderer renderer({.k = kK, .d = 5.0});
  PenaltySumOutput out;
  const Pose above{Vec3(0.0, 0.0, 0.5), Quat::Identity()};
  renderer.Tick(FloorIr(above), above, kDt, &out);
  EXPECT_EQ(out.contacts, 0);
  EXPECT_EQ(out.w_W.f.norm() + out.w_W.tau.norm(), 0.0);
  const Pose in{Vec3(0.0, 0.0, kHalf - kDepth), Quat::Identity()};
  renderer.Tick(FloorIr(in), in, kDt, &out);
  EXPECT_EQ(out.reactions[0].w_W.f.norm(), 0.0);
}

TEST(PenaltySum, BadInputGivesZeroAndAStatus) {
  PenaltySumRenderer renderer({.k = kK, .d = 0.0});
  PenaltySumOutput out;
  Pose X_WP{Vec3(0.0, 0.0, kHalf - kDepth), Quat::Identity()};
  TickIr ir = FloorIr(X_WP);
  ir.points[0].depth = std::nan("");
  renderer.Tick(ir, X_WP, kDt, &out);
  EXPECT_EQ(out.status, kProxyStatusBadInput);
  EXPECT_EQ(out.w_W.f.norm(), 0.0);
  EXPECT_THROW(PenaltySumRenderer({.k = -1.0}), InvalidArgument);
}

TEST(PenaltySum, TickDoesNotAllocate) {
  PenaltySumRenderer renderer({.k = kK, .d = 1.0});
  PenaltySumOutput out;
  const Pose X_WP{Vec3(0.0, 0.0, kHalf - kDepth), Quat::Identity()};
  const TickIr ir = FloorIr(X_WP);
  const mrh::testing::AllocGuard guard;
  for (int i = 0; i < 3; ++i) renderer.Tick(ir, X_WP, kDt, &out);
  EXPECT_EQ(guard.count(), 0);
}

}  // namespace
}  // namespace mrh::render
