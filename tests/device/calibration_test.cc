// SPDX-License-Identifier: Apache-2.0
// Tests of the device → world calibration (scale + rigid transform).
#include "mrh/device/calibration.h"

#include <gtest/gtest.h>

#include <numbers>

namespace mrh::device {
namespace {

// Values are O(1) m and rad; a few rotations and one scale lose a few ulps.
constexpr double kTol = 1e-12;

Calibration MakeCalibration() {
  Calibration c;
  c.X_WD.p = Vec3(1.0, 2.0, 3.0);
  c.X_WD.q = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));
  c.scale = 2.0;
  return c;
}

TEST(CalibrationTest, ToWorldScalesThenRotatesThenTranslatesPosition) {
  const Calibration c = MakeCalibration();
  Pose X_DT;
  X_DT.p = Vec3(1.0, 0.0, 0.0);
  // Rz(90°) maps (2, 0, 0) to (0, 2, 0).
  const Pose X_WT = c.ToWorld(X_DT);
  EXPECT_TRUE(X_WT.p.isApprox(Vec3(1.0, 4.0, 3.0), kTol)) << X_WT.p.transpose();
  EXPECT_TRUE(X_WT.q.isApprox(c.X_WD.q, kTol));
}

TEST(CalibrationTest, PoseRoundTripsThroughWorldAndBack) {
  const Calibration c = MakeCalibration();
  Pose X_DT;
  X_DT.p = Vec3(0.1, -0.2, 0.3);
  X_DT.q = Quat(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -1.0).normalized()));
  const Pose back = c.ToDevice(c.ToWorld(X_DT));
  EXPECT_LT((back.p - X_DT.p).norm(), kTol);
  EXPECT_LT(back.q.angularDistance(X_DT.q), kTol);
}

TEST(CalibrationTest, WorldPoseRoundTripsThroughDeviceAndBack) {
  const Calibration c = MakeCalibration();
  Pose X_WT;
  X_WT.p = Vec3(-0.5, 0.25, 2.0);
  X_WT.q = Quat(Eigen::AngleAxisd(-1.2, Vec3(0.0, 1.0, 1.0).normalized()));
  const Pose back = c.ToWorld(c.ToDevice(X_WT));
  EXPECT_LT((back.p - X_WT.p).norm(), kTol);
  EXPECT_LT(back.q.angularDistance(X_WT.q), kTol);
}

TEST(CalibrationTest, TwistScalesLinearVelocityButNotAngularVelocity) {
  const Calibration c = MakeCalibration();
  const Twist V_W = c.ToWorld(Twist{Vec3(1.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0)});
  EXPECT_TRUE(V_W.v.isApprox(Vec3(0.0, 2.0, 0.0), kTol)) << V_W.v.transpose();
  EXPECT_TRUE(V_W.w.isApprox(Vec3(0.0, 1.0, 0.0), kTol)) << V_W.w.transpose();
}

TEST(CalibrationTest, WrenchToDeviceRotatesWithoutScaling) {
  const Calibration c = MakeCalibration();
  const Wrench w_D = c.ToDevice(Wrench{Vec3(0.0, 3.0, 0.0), Vec3(0.0, 0.0, 0.5)});
  EXPECT_TRUE(w_D.f.isApprox(Vec3(3.0, 0.0, 0.0), kTol)) << w_D.f.transpose();
  EXPECT_TRUE(w_D.tau.isApprox(Vec3(0.0, 0.0, 0.5), kTol)) << w_D.tau.transpose();
}

TEST(CalibrationTest, DefaultCalibrationIsIdentity) {
  const Calibration c;
  Pose X_DT;
  X_DT.p = Vec3(0.3, 0.2, 0.1);
  X_DT.q = Quat(Eigen::AngleAxisd(0.4, Vec3::UnitY()));
  const Pose X_WT = c.ToWorld(X_DT);
  EXPECT_TRUE(X_WT.p.isApprox(X_DT.p, kTol));
  EXPECT_TRUE(X_WT.q.isApprox(X_DT.q, kTol));
}

}  // namespace
}  // namespace mrh::device
