// SPDX-License-Identifier: Apache-2.0
// grasp's two-hands and slide cases: each hand feels Coulomb's μ m g of its own box, whether
// or not the other hand pushes; a box squeezed between two fingers is dragged sideways with
// Coulomb's sliding force; the local-dynamics methods at 20 ms match single-rate at 1 ms.
#include <gtest/gtest.h>

#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kGravity = 9.81;   // m/s², the scenes'
constexpr double kFloorMu = 0.5;    // the scenes' box–floor friction
constexpr double kForceTol = 0.05;  // relative, the acceptance force bar
// scenes/two_hands_push.xml: the left box is 0.5 kg, the right 0.3 kg.
constexpr double kCoulomb[2] = {kFloorMu * 0.5 * kGravity, kFloorMu * 0.3 * kGravity};

void ExpectEachHandFeelsItsOwnBox(const GraspRun& run) {
  const HandsResult both = RunHandsCase({}, run, {0, 1});
  for (int i = 0; i < 2; ++i) {
    SCOPED_TRACE(i == 0 ? "left hand" : "right hand");
    EXPECT_NEAR(both.mean_force[i], kCoulomb[i], kForceTol * kCoulomb[i]);
    const HandsResult alone = RunHandsCase({}, run, {i});
    EXPECT_EQ(alone.mean_force[1 - i], 0.0);  // the other hand was not there
    EXPECT_NEAR(both.mean_force[i], alone.mean_force[i], kForceTol * alone.mean_force[i]);
    // Touched at 1 s, then pushed at 0.1 m/s to the end at 4 s.
    EXPECT_NEAR(both.travel[i], 0.3, 0.01);
  }
}

TEST(GraspHandsTest, SingleRateEachHandFeelsItsOwnBoxsCoulombForce) {
  ExpectEachHandFeelsItsOwnBox(GraspRun{"single-rate", 0.001});
}

// The acceptance bar for two hands, at 20 ms.
TEST(GraspHandsTest, LocalDynamicsAt20MsEachHandFeelsItsOwnBoxsCoulombForce) {
  ExpectEachHandFeelsItsOwnBox(GraspRun{"local-dynamics", 0.02});
}

TEST(GraspHandsTest, LocalDynamics6dofAt20MsEachHandFeelsItsOwnBoxsCoulombForce) {
  ExpectEachHandFeelsItsOwnBox(GraspRun{"local-dynamics-6dof", 0.02});
}

TEST(GraspSlideTest, SingleRateDragsTheSqueezedBoxWithCoulombsForce) {
  const SlideResult r = RunSlideCase({}, GraspRun{"single-rate", 0.001});
  const double weight = r.box_mass * kGravity;
  EXPECT_NEAR(r.box_mass, 0.2, 1e-12);  // the scene's
  // The floor carries what the fingers do not; sliding, it resists with μ times that load.
  EXPECT_NEAR(r.push_force, kFloorMu * (weight - r.carried), kForceTol * kFloorMu * weight);
  EXPECT_NEAR(r.box_travel, 0.1, 0.005);     // the fingers' travel: the box did not slip
  EXPECT_GT(r.mean_force[0], r.push_force);  // a squeeze, not a push
}

TEST(GraspSlideTest, LocalDynamicsMethodsAt20MsSlideAsSingleRateAt1Ms) {
  const SlideResult ref = RunSlideCase({}, GraspRun{"single-rate", 0.001});
  for (const char* method : {"local-dynamics", "local-dynamics-6dof"}) {
    SCOPED_TRACE(method);
    const SlideResult r = RunSlideCase({}, GraspRun{method, 0.02});
    EXPECT_NEAR(r.box_travel, ref.box_travel, 0.005);
    for (int finger = 0; finger < 2; ++finger) {
      EXPECT_NEAR(r.mean_force[finger], ref.mean_force[finger], kForceTol * ref.mean_force[finger])
          << "finger " << finger;
      EXPECT_LE(r.sd_force[finger], 2.0 * ref.sd_force[finger]) << "finger " << finger;
    }
    EXPECT_TRUE(MeetsSlideBars(r, ref));
    // The push is Coulomb's for the box's load on the floor (which the fingers' vertical
    // friction changes: it is statically indeterminate, so it is not compared with the
    // reference's).
    const double weight = r.box_mass * kGravity;
    EXPECT_NEAR(r.push_force, kFloorMu * (weight - r.carried), kForceTol * kFloorMu * weight);
  }
}

}  // namespace
}  // namespace mrh::experiments::internal
