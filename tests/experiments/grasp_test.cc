// SPDX-License-Identifier: Apache-2.0
// grasp: two simulated fingertips with 3-DOF friction pinch a 0.2 kg box, lift it
// 5 cm and hold it; the hold is checked against mechanics, not against another run.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kLift = 0.05;          // m, the pinch's lift
constexpr double kHandStiffness = 300;  // N/m, device::HandSettings' default pull
constexpr double kStiffness = 800;      // N/m, the driver's rendering.stiffness
constexpr double kHeightTol = 0.001;    // m
constexpr double kForceTol = 0.05;      // relative, the acceptance force bar
constexpr double kGravity = 9.81;       // m/s², the scene's

TEST(GraspTest, SingleRateLiftsAndHoldsTheBox) {
  const GraspResult r = RunGraspCase({}, GraspRun{"single-rate", 0.001});
  // The box rose with the fingers: 5 cm, less the sag under half its weight per finger of the
  // hand's spring toward its target and of the stick spring (the contact stiffness) in series.
  const double weight = r.box_mass * kGravity;
  const double sag = 0.5 * weight * (1.0 / kHandStiffness + 1.0 / kStiffness);
  EXPECT_NEAR(r.hold_height, kLift - sag, kHeightTol);
  // At rest in the fingers, the fingers carry its whole weight (friction's vertical share).
  EXPECT_NEAR(r.mean_lift_force, weight, kForceTol * weight);
  // A symmetric pinch: each finger's mean force within 5 % of the other's.
  EXPECT_NEAR(r.mean_force[0], r.mean_force[1], kForceTol * r.mean_force[1]);
  EXPECT_GT(r.mean_force[0], weight / 2.0);  // a squeeze, not a touch
}

// The essential result: at 20 ms the local-dynamics methods lift and hold the box as
// single-rate does at 1 ms: hold height within 5 mm, each finger's mean force within 5 %, force
// sd at most 2x the reference's; the fingers carry the weight.
TEST(GraspTest, LocalDynamicsMethodsAt20MsHoldAsSingleRateAt1Ms) {
  const GraspResult ref = RunGraspCase({}, GraspRun{"single-rate", 0.001});
  for (const char* method : {"local-dynamics", "local-dynamics-6dof"}) {
    SCOPED_TRACE(method);
    const GraspResult r = RunGraspCase({}, GraspRun{method, 0.02});
    EXPECT_NEAR(r.hold_height, ref.hold_height, 0.005);
    for (int finger = 0; finger < 2; ++finger) {
      EXPECT_NEAR(r.mean_force[finger], ref.mean_force[finger], kForceTol * ref.mean_force[finger])
          << "finger " << finger;
      EXPECT_LE(r.sd_force[finger], 2.0 * ref.sd_force[finger]) << "finger " << finger;
    }
    const double weight = r.box_mass * kGravity;
    EXPECT_NEAR(r.mean_lift_force, weight, kForceTol * weight);
    EXPECT_TRUE(MeetsBars(r, ref));
  }
}

}  // namespace
}  // namespace mrh::experiments::internal
