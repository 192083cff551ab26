// SPDX-License-Identifier: Apache-2.0
// The device model table: every supported model is there, and its limits are sane.
#include "mrh/device/models.h"

#include <gtest/gtest.h>

namespace mrh::device {
namespace {

TEST(DeviceModelsTest, EveryRequiredModelIsKnown) {
  for (const char* name : {"touch", "touch_x", "phantom_premium_1.5", "falcon", "omega.3",
                           "omega.6", "omega.7", "sigma.7", "lambda.7", "inverse3"}) {
    EXPECT_NE(FindDeviceModel(name), nullptr) << name;
  }
  EXPECT_EQ(FindDeviceModel("omega"), nullptr);
}

TEST(DeviceModelsTest, ThreeDofModelsHaveNoTorqueAndSixDofModelsDo) {
  for (const DeviceModel& m : DeviceModels()) {
    const Specifications s = ModelSpecifications(m);
    EXPECT_TRUE(m.output_dof == 3 || m.output_dof == 6) << m.name;
    EXPECT_EQ(s.has_torque, m.output_dof == 6) << m.name;
    EXPECT_EQ(m.max_torque > 0.0, m.output_dof == 6) << m.name;
    EXPECT_GT(s.max_force, 0.0) << m.name;
    EXPECT_GT(s.max_stiffness, 0.0) << m.name;
    EXPECT_EQ(s.workspace_max.x(), m.workspace_radius) << m.name;
    EXPECT_EQ(s.model, m.name);
  }
}

}  // namespace
}  // namespace mrh::device
