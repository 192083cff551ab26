// SPDX-License-Identifier: Apache-2.0
// Tests of the proxy pose the viewer infers from the rendered wrench and the coupling gains.
#include "viewer/overlay.h"

#include <gtest/gtest.h>

namespace mrh::viewer::internal {
namespace {

// Poses are O(0.1 m) and O(1 rad); a handful of operations each.
constexpr double kTol = 1e-12;

const Pose kPointer{Vec3(0.1, -0.2, 0.3), Quat(Eigen::AngleAxisd(0.4, Vec3::UnitX()))};
const Coupling kCoupling{.pointer_body = 1, .stiffness = 1000.0, .rot_stiffness = 10.0};

TEST(InferProxyTest, IsThePointerWhenNoWrenchIsRendered) {
  const Pose X_WQ = InferProxy(kPointer, Wrench{}, kCoupling);
  EXPECT_TRUE(X_WQ.p.isApprox(kPointer.p, kTol));
  EXPECT_NEAR(X_WQ.q.angularDistance(kPointer.q), 0.0, kTol);
}

TEST(InferProxyTest, SitsWhereTheSpringGivesTheRenderedForce) {
  // f = k (p_Q − p_P): 5 N at 1000 N/m is 5 mm along the force.
  const Pose X_WQ = InferProxy(kPointer, Wrench{Vec3(0.0, 0.0, 5.0), Vec3::Zero()}, kCoupling);
  EXPECT_TRUE(X_WQ.p.isApprox(kPointer.p + Vec3(0.0, 0.0, 0.005), kTol));
}

TEST(InferProxyTest, IsTurnedByTorqueOverRotationalStiffness) {
  // τ = k_r Δθ: 0.5 N·m at 10 N·m/rad is 0.05 rad about the torque's axis (world frame).
  const Pose X_WQ = InferProxy(kPointer, Wrench{Vec3::Zero(), Vec3(0.0, 0.0, 0.5)}, kCoupling);
  const Quat expected = Quat(Eigen::AngleAxisd(0.05, Vec3::UnitZ())) * kPointer.q;
  EXPECT_NEAR(X_WQ.q.angularDistance(expected), 0.0, kTol);
  EXPECT_TRUE(X_WQ.p.isApprox(kPointer.p, kTol));
}

TEST(InferProxyTest, AZeroGainLeavesThatPartAtThePointer) {
  const Coupling no_springs{.pointer_body = 1, .stiffness = 0.0, .rot_stiffness = 0.0};
  const Pose X_WQ = InferProxy(kPointer, Wrench{Vec3(1, 2, 3), Vec3(0.1, 0.2, 0.3)}, no_springs);
  EXPECT_TRUE(X_WQ.p.isApprox(kPointer.p, kTol));
  EXPECT_NEAR(X_WQ.q.angularDistance(kPointer.q), 0.0, kTol);
}

}  // namespace
}  // namespace mrh::viewer::internal
