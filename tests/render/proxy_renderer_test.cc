// SPDX-License-Identifier: Apache-2.0
// Tests of the 6-DOF proxy renderer (thesis §3.2.2–3.2.4, eq. 3.1–3.10): wrench, friction states,
// moving objects, reactions, dampers and warm starts; its RT contract and errors are in
// proxy_renderer_contract_test.cc.
#include "mrh/render/proxy_renderer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "mrh/core/error.h"
#include "proxy_rig.h"
#include "support/alloc_guard.h"

namespace mrh::render {
namespace {

using namespace proxy_rig;  // NOLINT(google-build-using-namespace): the test vocabulary

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(ProxyRendererTest, SingleContactBelowTheCentrePushesStraightOutWithoutTorque) {
  Rig rig(T31());
  const ProxyOutput& out = rig.Tick({Floor({Vec3(0, 0, -kHalf)})}, Pressed());
  EXPECT_LT((out.w_W.f - kKt * kDepth * Vec3::UnitZ()).norm(), kForceTol);
  EXPECT_LT(out.w_W.tau.norm(), kForceTol);
  EXPECT_LT((out.X_WQ.p - (Pressed().p + kDepth * Vec3::UnitZ())).norm(), 1e-9);
  EXPECT_EQ(out.diagnostics.contacts, 1);
}

TEST(ProxyRendererTest, FaceContactGivesKtTimesDepthWhateverTheContactCount) {
  Rig rig(T31());
  const ProxyOutput& out = rig.Tick({Floor(BottomFace())}, Pressed());
  EXPECT_EQ(out.diagnostics.contacts, 4);
  EXPECT_LT((out.w_W.f - kKt * kDepth * Vec3::UnitZ()).norm(), kForceTol);
  EXPECT_LT(out.w_W.tau.norm(), kForceTol);
}

TEST(ProxyRendererTest, FortyFiveDegreeEdgeContactGivesKtTimesDepthWithoutTorque) {
  // Turned 45° about x, the edge y_P = z_P = −0.1 lies at z = −0.1√2 below the centre.
  const Quat q = About(Vec3::UnitX(), std::numbers::pi / 4);
  const Pose X_WP{Vec3(0, 0, kHalf * std::sqrt(2.0) - kDepth), q};
  Rig rig(T31());
  const ProxyOutput& out =
      rig.Tick({Floor({Vec3(kHalf, -kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf)})}, X_WP);
  EXPECT_EQ(out.diagnostics.contacts, 2);
  EXPECT_LT((out.w_W.f - kKt * kDepth * Vec3::UnitZ()).norm(), kForceTol);
  EXPECT_LT(out.w_W.tau.norm(), kForceTol);
}

TEST(ProxyRendererTest, TiltedEdgeContactGivesTorqueWithTheSignOfTheLever) {
  // Turned +30° about x, the lowest edge is at y = r_y < 0: the floor pushes up behind the
  // centre, τ_x < 0. Symmetric pair of rows with R_w = w I: τ_x = k_r δ r_y / (w + r_y²).
  const double angle = std::numbers::pi / 6;
  const Quat q = About(Vec3::UnitX(), angle);
  const Vec3 corner(0, -kHalf, -kHalf);
  const Vec3 r = q * corner;
  const Pose X_WP{Vec3(0, 0, -r.z() - kDepth), q};
  Rig rig(T31());
  const ProxyOutput& out =
      rig.Tick({Floor({Vec3(kHalf, -kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf)})}, X_WP);
  const double w = 3.33;
  EXPECT_LT(r.y(), 0.0);
  EXPECT_NEAR(out.w_W.tau.x(), kKr * kDepth * r.y() / (w + r.y() * r.y()), kForceTol);
  EXPECT_LT(out.w_W.tau.x(), 0.0);
  EXPECT_NEAR(out.w_W.f.z(), kKt * kDepth / (1.0 + r.y() * r.y() / w), kForceTol);
}

TEST(ProxyRendererTest, KineticFrictionIsMuTimesTheNormalForceAgainstTheMotion) {
  Rig rig(Friction());
  const std::vector<PairSpec> floor{Floor({Vec3(0, 0, -kHalf)})};
  (void)rig.Tick(floor, Pressed());
  for (int tick = 1; tick <= 5; ++tick) {
    const double u = 4.0 * kMu * kDepth * tick;  // beyond the cone radius μδ every tick
    const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3(u, 0, 0)));
    EXPECT_EQ(out.diagnostics.sliding_rows, 1) << "tick " << tick;
    EXPECT_NEAR(out.w_W.f.z(), kKt * kDepth, kForceTol);
    EXPECT_NEAR(out.w_W.f.x(), -kMu * kKt * kDepth, kForceTol) << "tick " << tick;
    EXPECT_NEAR(out.w_W.f.y(), 0.0, kForceTol);
  }
}

TEST(ProxyRendererTest, StaticFrictionKeepsTheProxyPointWhereItWas) {
  Rig rig(Friction());
  const std::vector<PairSpec> floor{Floor({Vec3(0, 0, -kHalf)})};
  const Vec3 p_PV(0, 0, -kHalf);
  const Vec3 stuck = rig.Tick(floor, Pressed()).X_WQ * p_PV;
  const double u = 0.4 * kMu * kDepth;  // inside the cone
  for (int tick = 0; tick < 3; ++tick) {
    const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3(u, 0, 0)));
    EXPECT_EQ(out.diagnostics.sticking_rows, 1);
    EXPECT_LT((out.X_WQ * p_PV - stuck).norm(), 1e-9);
    EXPECT_NEAR(out.w_W.f.x(), -kKt * u, kForceTol);
    EXPECT_LT(std::abs(out.w_W.f.x()), kMu * out.w_W.f.z());
  }
}

TEST(ProxyRendererTest, FirstTickOfAContactSticksWhateverThePointerDidBefore) {
  Rig rig(Friction());
  const std::vector<PairSpec> floor{Floor({Vec3(0, 0, -kHalf)})};
  (void)rig.Tick(floor, Pressed(Vec3(0, 0, 0.05)));  // above the floor
  const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3(0.05, 0, 0)));
  EXPECT_EQ(out.diagnostics.contacts, 1);
  EXPECT_EQ(out.diagnostics.sticking_rows + out.diagnostics.sliding_rows, 0);
  EXPECT_EQ(out.w_W.f.x(), 0.0);
}

TEST(ProxyRendererTest, NoContactGivesZeroWrenchWhateverTheMotion) {
  ProxyRendererSettings settings = Friction(3.33 * Mat3::Identity());
  settings.d_t = 10.0;
  settings.d_r = 1.0;
  Rig rig(settings);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::vector<PairSpec> floor{Floor(BottomFace())};
  for (int tick = 0; tick < 500; ++tick) {
    // Above z = 0.2 m the cube (half diagonal 0.173 m) never reaches the floor.
    const Vec3 p(unit(rng), unit(rng), 0.6 + 0.4 * unit(rng));
    const Quat q = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
    const ProxyOutput& out = rig.Tick(tick % 2 == 0 ? floor : std::vector<PairSpec>{}, {p, q});
    ASSERT_EQ(out.diagnostics.contacts, 0);
    EXPECT_EQ(out.w_W.f.norm(), 0.0) << "tick " << tick;
    EXPECT_EQ(out.w_W.tau.norm(), 0.0) << "tick " << tick;
  }
}

TEST(ProxyRendererTest, TwistingAFaceContactGivesATorqueOpposingTheTwist) {
  // Static case: every point slips |r_xy| φ < μδ, the proxy keeps the old angle: Δθ = −φ ẑ.
  Rig rig(Friction(3.33 * Mat3::Identity()));
  const std::vector<PairSpec> floor{Floor(BottomFace())};
  (void)rig.Tick(floor, Pressed());
  const double phi = 2e-3;
  const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3::Zero(), About(Vec3::UnitZ(), phi)));
  EXPECT_EQ(out.diagnostics.sticking_rows, 4);
  EXPECT_NEAR(out.w_W.tau.z(), -kKr * phi, 1e-3 * kKr * phi);
  EXPECT_LT(out.w_W.tau.head<2>().norm(), kForceTol);
}

TEST(ProxyRendererTest, TwistingBeyondTheConesGivesAWeakerOpposingTorque) {
  Rig rig(Friction(3.33 * Mat3::Identity()));
  const std::vector<PairSpec> floor{Floor(BottomFace())};
  (void)rig.Tick(floor, Pressed());
  const double phi = 0.05;
  const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3::Zero(), About(Vec3::UnitZ(), phi)));
  EXPECT_EQ(out.diagnostics.sliding_rows, 4);
  EXPECT_LT(out.w_W.tau.z(), 0.0);
  EXPECT_GT(out.w_W.tau.z(), -kKr * phi);
}

TEST(ProxyRendererTest, ContactCarriedWithAMovingObjectDoesNotSlip) {
  // Object and pointer move together, 2 mm (4× the cone radius) and 0.01 rad per tick.
  Rig rig(Friction(3.33 * Mat3::Identity()));
  for (int tick = 0; tick < 10; ++tick) {
    const Pose X_WB{Vec3(2e-3 * tick, 0, 0), About(Vec3::UnitZ(), 0.01 * tick)};
    const ProxyOutput& out = rig.Tick({Box(5, X_WB)}, X_WB * Pressed());
    EXPECT_EQ(out.diagnostics.sliding_rows, 0) << "tick " << tick;
    EXPECT_LT(out.w_W.f.head<2>().norm(), kForceTol) << "tick " << tick;
    EXPECT_NEAR(out.w_W.f.z(), kKt * kDepth, kForceTol);
  }
}

TEST(ProxyRendererTest, MovingObjectDragsTheStillPointerThroughStaticFriction) {
  Rig rig(Friction());
  (void)rig.Tick({Box(5, Pose{})}, Pressed());
  const double u = 0.4 * kMu * kDepth;
  const ProxyOutput& out = rig.Tick({Box(5, Pose{Vec3(u, 0, 0), Quat::Identity()})}, Pressed());
  EXPECT_EQ(out.diagnostics.sticking_rows, 4);
  EXPECT_NEAR(out.w_W.f.x(), kKt * u, kForceTol);
  EXPECT_NEAR(out.reactions[0].w_W.f.x(), -kKt * u, kForceTol);
}

TEST(ProxyRendererTest, ReactionsSumToMinusTheRenderedForceWithDamping) {
  ProxyRendererSettings settings = Friction(3.33 * Mat3::Identity());
  settings.d_t = 10.0;
  Rig rig(settings);
  // The face straddles two boxes: x < 0 on body 5, x > 0 on body 6.
  auto specs = [](const Vec3& shift) {
    PairSpec left = Box(5, Pose{shift, Quat::Identity()});
    left.points_P = {Vec3(-kHalf, kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf)};
    PairSpec right = Box(6, Pose{Vec3(0, 0, 0.2e-3), Quat::Identity()});
    right.key = 10;
    right.points_P = {Vec3(kHalf, kHalf, -kHalf), Vec3(kHalf, -kHalf, -kHalf)};
    return std::vector<PairSpec>{left, right};
  };
  (void)rig.Tick(specs(Vec3::Zero()), Pressed());
  const ProxyOutput& out = rig.Tick(specs(Vec3(1e-4, 0, 0)), Pressed(Vec3(0, 2e-4, -1e-4)));
  ASSERT_EQ(out.reactions.size(), 2u);
  const Vec3 sum = out.reactions[0].w_W.f + out.reactions[1].w_W.f;
  EXPECT_LT((sum + out.w_W.f).norm(), 1e-9 * out.w_W.f.norm());
  EXPECT_GT(out.diagnostics.sticking_rows, 0);
}

TEST(ProxyRendererTest, ReactionIsMinusTheRenderedWrenchAboutTheObjectCentreOfMass) {
  Rig rig(T31());
  const Vec3 p_PV(0.05, 0.02, -kHalf);
  PairSpec box = Box(5, Pose{});
  box.points_P = {p_PV};
  const ProxyOutput& one = rig.Tick({box}, Pressed());
  ASSERT_GT(one.w_W.tau.norm(), 0.0);
  // The only pair takes the whole wrench: −f at the pointer origin plus −τ, moved to the COM.
  const Vec3 force = -one.w_W.f;
  const Vec3 moment = -one.w_W.tau + (Pressed().p - box.p_BCm).cross(force);
  EXPECT_LT((one.reactions[0].w_W.f - force).norm(), 1e-12 * force.norm());
  EXPECT_LT((one.reactions[0].w_W.tau - moment).norm(), kForceTol);
}

TEST(ProxyRendererTest, ReactionsOfSeveralObjectsAddUpToMinusTheRenderedWrench) {
  // Two boxes under a twisted, sliding face with friction and dampers, at T3.2's weight where
  // the rows' own moments k_t f_k (r_k × a_k) would be thousands of times the felt torque.
  ProxyRendererSettings settings = Friction(Vec3(8420.0, 1670.0, 8420.0).asDiagonal());
  settings.k_r = 9000.0;
  settings.d_t = 10.0;
  settings.d_r = 1.0;
  Rig rig(settings);
  auto specs = [] {
    PairSpec left = Box(5, Pose{});
    left.points_P = {Vec3(-kHalf, kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf)};
    PairSpec right = Box(6, Pose{});
    right.key = 10;
    right.p_BCm = Vec3(0.3, -0.1, -0.2);
    right.points_P = {Vec3(kHalf, kHalf, -kHalf), Vec3(kHalf, -kHalf, -kHalf)};
    return std::vector<PairSpec>{left, right};
  };
  (void)rig.Tick(specs(), Pressed());
  const Pose X_WP = Pressed(Vec3(2e-4, 1e-4, -1e-4), About(Vec3::UnitZ(), 0.01));
  const ProxyOutput& out = rig.Tick(specs(), X_WP);
  ASSERT_EQ(out.reactions.size(), 2u);
  ASSERT_GT(out.diagnostics.sliding_rows + out.diagnostics.sticking_rows, 0);
  Wrench sum;  // about the pointer origin
  for (const ProxyPairReaction& r : out.reactions) {
    const Vec3 p_WCm = r.body == 5 ? Box(5, Pose{}).p_BCm : Vec3(0.3, -0.1, -0.2);
    sum.f += r.w_W.f;
    sum.tau += r.w_W.tau + (p_WCm - X_WP.p).cross(r.w_W.f);
  }
  EXPECT_LT((sum.f + out.w_W.f).norm(), 1e-9 * out.w_W.f.norm());
  EXPECT_LT((sum.tau + out.w_W.tau).norm(), 1e-9 * out.w_W.tau.norm());
  EXPECT_GT(out.w_W.tau.norm(), 1e-3);
}

TEST(ProxyRendererTest, EachObjectUnderAStraddlingPointerTakesItsForceWhereItIsTouched) {
  // A flat pointer pressed kDepth into two boxes, one point on each, mirrored about the pointer
  // origin: the proxy rises by kDepth without turning, each point carries k_t kDepth / 2, and
  // the pointer feels no torque. Each box then takes −k_t kDepth / 2 along n at its own point:
  // its moment about its COM is (p_k − c) × F. The renderer's own per-pair split τ_i = k_r Δθ_i
  // is ± k_r f R_w⁻¹ (r_k × n), which only cancels in the sum; −F_i placed at the pointer origin
  // would add a couple |r_k × F_i| to each box.
  Rig rig(T31());
  PairSpec left = Box(5, Pose{});
  left.p_BCm = Vec3(-0.05, 0.03, -0.05);
  left.points_P = {Vec3(-kHalf, 0, -kHalf)};
  PairSpec right = Box(6, Pose{});
  right.key = 10;
  right.p_BCm = Vec3(0.12, -0.02, -0.05);
  right.points_P = {Vec3(kHalf, 0, -kHalf)};
  const Pose X_WP = Pressed();
  const ProxyOutput& out = rig.Tick({left, right}, X_WP);
  ASSERT_EQ(out.reactions.size(), 2u);
  EXPECT_LT(out.w_W.tau.norm(), kForceTol);
  const double each = kKt * kDepth / 2.0;
  for (const PairSpec& box : {left, right}) {
    const ProxyPairReaction& r = out.reactions[box.body == 5 ? 0 : 1];
    const Vec3 force(0, 0, -each);
    const Vec3 moment = (X_WP * box.points_P[0] - box.p_BCm).cross(force);
    EXPECT_LT((r.w_W.f - force).norm(), kForceTol) << "box " << box.body;
    EXPECT_LT((r.w_W.tau - moment).norm(), kForceTol) << "box " << box.body;
  }
}

TEST(ProxyRendererTest, ImpulsesGoToMovingBodiesOnlySummedPerBody) {
  Rig rig(T31());
  // Three points not on a line, so each row's f is unique and every pair carries load.
  PairSpec a = Box(5, Pose{});
  a.points_P = {Vec3(-kHalf, -kHalf, -kHalf)};
  PairSpec b = Box(5, Pose{});
  b.key = 11;
  b.points_P = {Vec3(kHalf, -kHalf, -kHalf)};
  const ProxyOutput& out = rig.Tick({Floor({Vec3(0, kHalf, -kHalf)}), a, b}, Pressed());
  ir::HapticReport report;
  AddReactionImpulses(out, kDt, &report);
  ASSERT_EQ(report.impulses.size(), 1u);
  EXPECT_EQ(out.reactions[0].w_W.f.norm(), 0.0);  // the static floor takes no reaction
  const Vec3 force = out.reactions[1].w_W.f + out.reactions[2].w_W.f;
  EXPECT_EQ(report.impulses[0].body, 5);
  EXPECT_LT((report.impulses[0].linear - force * kDt).norm(), 1e-15);
  EXPECT_LT((report.impulses[0].last_force - force).norm(), 1e-12);
  EXPECT_LT(force.z(), 0.0);
}

TEST(ProxyRendererTest, DampersActOnTheChangeOfTheProxyOffset) {
  ProxyRendererSettings settings = T31();
  settings.d_t = 10.0;
  settings.d_r = 2.0;
  Rig rig(settings);
  const std::vector<PairSpec> floor{Floor({Vec3(0.05, 0, -kHalf)})};
  const Vec3 dr1 = rig.Tick(floor, Pressed()).dr;
  const Vec3 dtheta1 = rig.out->dtheta;
  const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3(0, 0, -5e-4)));
  EXPECT_LT((out.w_W.f - (kKt * out.dr + 10.0 * (out.dr - dr1) / kDt)).norm(), 1e-9);
  EXPECT_LT((out.w_W.tau - (kKr * out.dtheta + 2.0 * (out.dtheta - dtheta1) / kDt)).norm(), 1e-9);
  EXPECT_GT(out.dr.z(), dr1.z());
}

// A pointer that starts inside an object has no previous offset; its dampers start at
// rest instead of seeing the whole offset appear in one tick (15 N against a steady 5 N).
TEST(ProxyRendererTest, FirstTickAfterStartRendersTheSpringOnly) {
  ProxyRendererSettings settings = T31();
  settings.d_t = 10.0;
  settings.d_r = 2.0;
  Rig rig(settings);
  const ProxyOutput& out = rig.Tick({Floor({Vec3(0, 0, -kHalf)})}, Pressed());
  EXPECT_LT((out.w_W.f - kKt * kDepth * Vec3::UnitZ()).norm(), kForceTol);
  EXPECT_LT(out.w_W.tau.norm(), kForceTol);
}

TEST(ProxyRendererTest, PersistingContactsWarmStartAndConvergeInOneSweep) {
  ProxyRendererSettings settings = Friction(3.33 * Mat3::Identity());
  settings.solver = ProxySolverKind::kPgs;
  Rig rig(settings);
  const std::vector<PairSpec> floor{Floor(BottomFace())};
  (void)rig.Tick(floor, Pressed());
  (void)rig.Tick(floor, Pressed(Vec3(1e-4, 0, 0)));
  const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3(1e-4, 0, 0)));
  EXPECT_EQ(out.diagnostics.rows, 8);
  EXPECT_EQ(out.diagnostics.warm_rows, 8);
  EXPECT_EQ(out.diagnostics.iterations, 1);
}

TEST(ProxyRendererTest, HeldFaceContactConvergesAcrossTicksThroughTheWarmStart) {
  // With 50 sweeps a tick, the first tick leaves a rotation error (PGS is slow when
  // R_w ≫ |r|²); the warm start continues the iteration tick after tick until it converges.
  ProxyRendererSettings settings = T31();
  settings.solver = ProxySolverKind::kPgs;
  settings.max_iterations = 50;
  settings.tolerance = 1e-10;
  Rig rig(settings);
  const std::vector<PairSpec> floor{Floor(BottomFace())};
  const ProxyOutput& first = rig.Tick(floor, Pressed());
  EXPECT_FALSE(first.diagnostics.converged);
  EXPECT_GT(first.w_W.tau.norm(), 1e-3 * kKt * kDepth * kHalf);
  for (int tick = 0; tick < 100; ++tick) (void)rig.Tick(floor, Pressed());
  const ProxyOutput& out = rig.Tick(floor, Pressed());
  EXPECT_TRUE(out.diagnostics.converged);
  EXPECT_LT(out.w_W.tau.norm(), 1e-4 * kKt * kDepth * kHalf);
  EXPECT_LT((out.w_W.f - kKt * kDepth * Vec3::UnitZ()).norm(), 1e-4 * kKt * kDepth);
}

TEST(ProxyRendererTest, ActiveSetSolvesAHeldFaceContactExactlyOnTheFirstTick) {
  // What PGS reaches only after ~100 warm-started ticks (test above), in one tick.
  Rig rig(T31());
  const std::vector<PairSpec> floor{Floor(BottomFace())};
  const ProxyOutput& first = rig.Tick(floor, Pressed());
  EXPECT_TRUE(first.diagnostics.converged);
  EXPECT_LE(first.diagnostics.iterations, 4);
  EXPECT_LT(first.w_W.tau.norm(), 1e-9 * kKt * kDepth * kHalf);
  EXPECT_LT((first.w_W.f - kKt * kDepth * Vec3::UnitZ()).norm(), 1e-9 * kKt * kDepth);
  // Held: the warm start is the solution, so the next tick takes no step.
  const ProxyOutput& held = rig.Tick(floor, Pressed());
  EXPECT_TRUE(held.diagnostics.converged);
  EXPECT_EQ(held.diagnostics.iterations, 0);
}

TEST(ProxyRendererTest, RowUpdateBudgetCapsTheSweepsOfLargeContactSets) {
  ProxyRendererSettings settings = T31();
  settings.solver = ProxySolverKind::kPgs;
  settings.max_row_updates = 10;
  Rig rig(settings);
  const ProxyOutput& face = rig.Tick({Floor(BottomFace())}, Pressed());
  EXPECT_EQ(face.diagnostics.iterations, 2);  // 10 updates / 4 rows
  EXPECT_FALSE(face.diagnostics.converged);
  rig.renderer.Reset();
  const ProxyOutput& single = rig.Tick({Floor({Vec3(0, 0, -kHalf)})}, Pressed());
  EXPECT_TRUE(single.diagnostics.converged);  // 1 row: exact in one sweep, confirmed by the next
  EXPECT_EQ(single.diagnostics.iterations, 2);
}

TEST(ProxyRendererTest, ResetMakesTheNextTickAFirstContact) {
  Rig rig(Friction());
  const std::vector<PairSpec> floor{Floor({Vec3(0, 0, -kHalf)})};
  (void)rig.Tick(floor, Pressed());
  rig.renderer.Reset();
  const ProxyOutput& out = rig.Tick(floor, Pressed(Vec3(0.01, 0, 0)));
  EXPECT_EQ(out.diagnostics.rows, 1);
  EXPECT_EQ(out.diagnostics.warm_rows, 0);
}

}  // namespace
}  // namespace mrh::render
