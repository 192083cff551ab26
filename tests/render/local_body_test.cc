// SPDX-License-Identifier: Apache-2.0
// Tests of the haptic-thread local rigid body (eq. 4.14–4.15) and its sphere penalty contact.
#include "mrh/render/local_body.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace mrh::render {
namespace {

constexpr double kDt = 0.001;  // s, one haptic tick
constexpr double kMass = 2.0;  // kg
// Quantities of order 1 after a few hundred operations.
constexpr double kTol = 1e-12;

// Accelerance of a 2 kg point-like body: linear rows 1/m, no rotation.
ir::Mat63 PointMassA() {
  ir::Mat63 A = ir::Mat63::Zero();
  A.topRows<3>() = Mat3::Identity() / kMass;
  return A;
}

TEST(LocalBodyTest, ConstantForceGivesUniformAccelerationWithSemiImplicitPositions) {
  LocalBody body;
  body.Reset(Pose{Vec3(0.1, 0, 0), Quat::Identity()}, Vec3::Zero(), Twist{});
  Vec6 b = Vec6::Zero();
  b.z() = -9.81;
  body.SetDynamics(PointMassA(), b);
  const Vec3 f(4.0, 0, 0);  // a = 2 m/s² along x, g along −z
  const int ticks = 100;
  for (int i = 0; i < ticks; ++i) ASSERT_TRUE(body.Step(f, kDt));
  const double t = ticks * kDt;
  EXPECT_NEAR(body.V_WCm().v.x(), 2.0 * t, kTol);
  EXPECT_NEAR(body.V_WCm().v.z(), -9.81 * t, kTol);
  // Semi-implicit Euler: x_n = x_0 + a Δt² n(n+1)/2.
  EXPECT_NEAR(body.p_WCm().x(), 0.1 + 2.0 * kDt * kDt * ticks * (ticks + 1) / 2.0, kTol);
}

TEST(LocalBodyTest, WorldAngularVelocityRotatesAboutTheWorldAxisAndKeepsUnitQuaternion) {
  LocalBody body;
  const Quat q0(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  const Vec3 w_W(0.0, 0.0, 30.0);  // rad/s, about world z, far from any body axis
  body.Reset(Pose{Vec3::Zero(), q0}, Vec3::Zero(), Twist{Vec3::Zero(), w_W});
  const int ticks = 1000;
  for (int i = 0; i < ticks; ++i) ASSERT_TRUE(body.Step(Vec3::Zero(), kDt));
  const Quat expected = Quat(Eigen::AngleAxisd(30.0 * ticks * kDt, Vec3::UnitZ())) * q0;
  EXPECT_NEAR(body.X_WB().q.norm(), 1.0, 1e-15);
  EXPECT_LT(body.X_WB().q.angularDistance(expected), 1e-10);
}

TEST(LocalBodyTest, BodyFramePoseFollowsTheCentreOfMass) {
  LocalBody body;
  const Vec3 p_BCm(0.05, 0, 0);
  body.Reset(Pose{Vec3(1, 0, 0), Quat::Identity()}, p_BCm, Twist{Vec3::Zero(), Vec3(0, 0, 1)});
  EXPECT_NEAR((body.p_WCm() - Vec3(1.05, 0, 0)).norm(), 0.0, kTol);
  ASSERT_TRUE(body.Step(Vec3::Zero(), 0.5 * std::numbers::pi));  // a quarter turn about z
  // The COM stays; the body origin swings around it.
  EXPECT_NEAR((body.X_WB().p - Vec3(1.05, -0.05, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((body.PointVelocity(body.X_WB().p) - Vec3(0.05, 0, 0)).norm(), 0.0, kTol);
}

TEST(LocalBodyTest, AcceleranceAngularRowsTurnTheBody) {
  LocalBody body;
  body.Reset(Pose{}, Vec3::Zero(), Twist{});
  ir::Mat63 A = ir::Mat63::Zero();
  A(5, 0) = 3.0;  // force along x at a point below the COM: spins about z
  body.SetDynamics(A, Vec6::Zero());
  ASSERT_TRUE(body.Step(Vec3(2.0, 0, 0), kDt));
  EXPECT_NEAR(body.V_WCm().w.z(), 6.0 * kDt, kTol);
  EXPECT_EQ(body.V_WCm().v, Vec3::Zero());
}

TEST(LocalBodyTest, AddedVelocityJumpsOnce) {
  LocalBody body;
  body.Reset(Pose{}, Vec3::Zero(), Twist{Vec3(1, 0, 0), Vec3::Zero()});
  body.AddVelocity(Twist{Vec3(-0.25, 0, 0), Vec3(0, 0.5, 0)});
  EXPECT_EQ(body.V_WCm().v, Vec3(0.75, 0, 0));
  EXPECT_EQ(body.V_WCm().w, Vec3(0, 0.5, 0));
}

TEST(LocalBodyTest, NonFiniteResultKeepsPoseAndStopsTheBody) {
  LocalBody body;
  body.Reset(Pose{Vec3(0.2, 0, 0), Quat::Identity()}, Vec3::Zero(), Twist{Vec3(1, 0, 0), {}});
  body.SetDynamics(PointMassA(), Vec6::Zero());
  EXPECT_FALSE(body.Step(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0), kDt));
  EXPECT_EQ(body.p_WCm(), Vec3(0.2, 0, 0));
  EXPECT_EQ(body.V_WCm().v, Vec3::Zero());
  EXPECT_TRUE(body.Step(Vec3::Zero(), kDt));
}

TEST(LocalBodyTest, SpherePushedIntoBodyGetsSpringForceOutAndBodyGetsReaction) {
  LocalBody body;
  // A plane on the body's +x face at x = 0.1, body at rest.
  body.Reset(Pose{}, Vec3::Zero(), Twist{});
  const Vec3 p_BC(0.1, 0, 0);
  const double radius = 0.02;
  const Vec3 p_WP(0.1 + radius - 0.003, 0, 0);  // 3 mm deep
  const SphereContact c = body.TouchSphere(p_BC, Vec3::UnitX(), p_WP, Twist{}, radius, 1000.0, 0.0);
  EXPECT_NEAR(c.result.depth, 0.003, kTol);
  EXPECT_NEAR((c.result.f_W - Vec3(3.0, 0, 0)).norm(), 0.0, kTol);  // pushes the pointer out
  EXPECT_NEAR((c.state.p_WO - p_BC).norm(), 0.0, kTol);
}

TEST(LocalBodyTest, PlaneMovesWithTheBodyAndItsVelocityFeedsTheDamper) {
  LocalBody body;
  const Vec3 p_BC(0.1, 0, 0);
  const double radius = 0.02;
  // The body has moved 2 mm toward the pointer since the IR was built, and keeps moving.
  body.Reset(Pose{Vec3(0.002, 0, 0), Quat::Identity()}, Vec3::Zero(),
             Twist{Vec3(0.1, 0, 0), Vec3::Zero()});
  const Vec3 p_WP(0.1 + radius, 0, 0);  // just touching the plane where it was built
  const SphereContact c =
      body.TouchSphere(p_BC, Vec3::UnitX(), p_WP, Twist{}, radius, 1000.0, 10.0);
  EXPECT_NEAR(c.result.depth, 0.002, kTol);
  EXPECT_NEAR(c.result.magnitude, 1000.0 * 0.002 + 10.0 * 0.1, kTol);
}

TEST(LocalBodyTest, SeparatedSphereFeelsNothing) {
  LocalBody body;
  body.Reset(Pose{}, Vec3::Zero(), Twist{});
  const SphereContact c = body.TouchSphere(Vec3(0.1, 0, 0), Vec3::UnitX(), Vec3(0.2, 0, 0),
                                           Twist{Vec3(-1, 0, 0), {}}, 0.02, 1000.0, 50.0);
  EXPECT_EQ(c.result.f_W, Vec3::Zero());
}

}  // namespace
}  // namespace mrh::render
