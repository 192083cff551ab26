// SPDX-License-Identifier: Apache-2.0
// Tests of the mouse → pointer mapping: the pointer follows the cursor at its depth.
#include "viewer/pointer_control.h"

#include <gtest/gtest.h>

#include <numbers>

namespace mrh::viewer::internal {
namespace {

// Poses are O(1 m); a handful of operations each.
constexpr double kTol = 1e-12;

// A camera 2 m from the origin on +x, looking at it along −x with z up: right is +y. Its
// frustum is 0.8 high at unit distance, so at the pointer's depth one viewport height is 1.6 m.
world::CameraFrame Camera() {
  world::CameraFrame camera;
  camera.p_WC = Vec3(2.0, 0.0, 0.0);
  camera.forward_W = -Vec3::UnitX();
  camera.up_W = Vec3::UnitZ();
  camera.frustum_height = 0.8;
  return camera;
}

const Pose kTarget{Vec3::Zero(), Quat::Identity()};

TEST(PointerControlTest, AxesAtThePointerScaleAViewportHeightByItsDepth) {
  const ViewAxes a = AxesAt(Camera(), kTarget.p);
  EXPECT_TRUE(a.right.isApprox(Vec3::UnitY(), kTol));
  EXPECT_NEAR(a.depth, 2.0, kTol);
  EXPECT_NEAR(a.metres_per_height, 1.6, kTol);
}

TEST(PointerControlTest, LeftDragMovesThePointerWithTheCursorInTheViewPlane) {
  // A tenth of the height right and a twentieth down: 0.16 m right (+y), 0.08 m down (−z).
  Pose X_WT = kTarget;
  MovePointer(AxesAt(Camera(), X_WT.p), PointerDrag{.left = true, .rx = 0.1, .ry = 0.05}, &X_WT);
  EXPECT_TRUE(X_WT.p.isApprox(Vec3(0.0, 0.16, -0.08), kTol));
  EXPECT_NEAR(X_WT.q.angularDistance(kTarget.q), 0.0, kTol);
}

TEST(PointerControlTest, ShiftLeftDragUpPushesThePointerAwayFromTheEye) {
  Pose X_WT = kTarget;
  MovePointer(AxesAt(Camera(), X_WT.p), PointerDrag{.left = true, .shift = true, .ry = -0.1},
              &X_WT);
  EXPECT_TRUE(X_WT.p.isApprox(Vec3(-0.16, 0.0, 0.0), kTol));
}

TEST(PointerControlTest, RightDragTurnsThePointerHalfATurnPerViewportHeight) {
  // Sideways by half the height: a quarter turn about the camera's up axis (world z).
  Pose X_WT = kTarget;
  MovePointer(AxesAt(Camera(), X_WT.p), PointerDrag{.right = true, .rx = 0.5}, &X_WT);
  const Quat expected(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));
  EXPECT_NEAR(X_WT.q.angularDistance(expected), 0.0, kTol);
  EXPECT_TRUE(X_WT.p.isApprox(kTarget.p, kTol));
}

TEST(PointerControlTest, WheelNotchMovesThePointerTwoPercentOfItsDepthAway) {
  Pose X_WT = kTarget;
  MovePointer(AxesAt(Camera(), X_WT.p), PointerDrag{.scroll = 1.0}, &X_WT);
  EXPECT_TRUE(X_WT.p.isApprox(Vec3(-0.04, 0.0, 0.0), kTol));
}

TEST(PointerControlTest, MotionWithoutADragLeavesThePointer) {
  Pose X_WT = kTarget;
  MovePointer(AxesAt(Camera(), X_WT.p), PointerDrag{.rx = 0.3, .ry = 0.2}, &X_WT);
  EXPECT_TRUE(X_WT.p.isApprox(kTarget.p, kTol));
  EXPECT_NEAR(X_WT.q.angularDistance(kTarget.q), 0.0, kTol);
}

}  // namespace
}  // namespace mrh::viewer::internal
