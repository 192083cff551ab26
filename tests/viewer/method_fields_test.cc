// SPDX-License-Identifier: Apache-2.0
// Tests of FieldsFor: the panel offers only the gains a method reads.
#include "viewer/method_fields.h"

#include <gtest/gtest.h>

namespace mrh::viewer::internal {
namespace {

TEST(MethodFieldsTest, ThreeDofMethodsShowStiffnessAndDampingOnlyAndNoTorque) {
  for (const char* method : {"single-rate", "impulse", "local-dynamics"}) {
    const MethodFields f = FieldsFor(method);
    EXPECT_TRUE(f.stiffness) << method;
    EXPECT_FALSE(f.friction) << method;
    EXPECT_FALSE(f.rot_stiffness) << method;
    EXPECT_FALSE(f.coupling) << method;
    EXPECT_FALSE(f.torque) << method;
  }
}

TEST(MethodFieldsTest, ProxyMethodsShowFrictionRotationalStiffnessAndTorque) {
  for (const char* method : {"proxy-6dof", "local-dynamics-6dof"}) {
    const MethodFields f = FieldsFor(method);
    EXPECT_TRUE(f.stiffness && f.friction && f.rot_stiffness && f.torque) << method;
    EXPECT_FALSE(f.coupling) << method;
  }
}

TEST(MethodFieldsTest, VirtualCouplingShowsTheCouplingGainsInsteadOfTheContactOnes) {
  const MethodFields f = FieldsFor("virtual-coupling");
  EXPECT_TRUE(f.coupling);
  EXPECT_FALSE(f.stiffness);
  EXPECT_FALSE(f.friction);
  EXPECT_TRUE(f.torque);
}

TEST(MethodFieldsTest, PenaltySumAndContactVolumeHaveNoRotationalStiffness) {
  EXPECT_FALSE(FieldsFor("penalty-sum").rot_stiffness);
  EXPECT_FALSE(FieldsFor("penalty-sum").friction);
  EXPECT_FALSE(FieldsFor("contact-volume").rot_stiffness);
  EXPECT_TRUE(FieldsFor("contact-volume").friction);
}

}  // namespace
}  // namespace mrh::viewer::internal
