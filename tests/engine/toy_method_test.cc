// SPDX-License-Identifier: Apache-2.0
// The worked example of docs/architecture.md (examples/toy_plane.h, examples/toy_line.h) in the
// build tree: a method and a device registered from outside the library run on a session.
#include <gtest/gtest.h>

#include <algorithm>

#include "mrh/engine/engine.h"
#include "mrh/session/devices.h"
#include "mrh/session/session.h"
#include "toy_line.h"
#include "toy_plane.h"

namespace mrh::engine::testing {
namespace {

TEST(ToyMethodTest, RegisteredMethodAndDeviceRunOnASession) {
  toy::RegisterToyPlane();
  toy::RegisterToyLine();
  const auto methods = ListMethods();
  EXPECT_TRUE(std::any_of(methods.begin(), methods.end(), [](const auto& m) {
    return m.first == "toy-plane";
  }));
  EXPECT_TRUE(session::FindDevice("toy-line").has_value());

  const session::Session session =
      session::LoadSession(MRH_SOURCE_DIR "/scenes/t4_1_impulse.json",
                           {"method=toy-plane", "mode=lockstep",
                            R"(device={"type": "toy-line", "limits": {"max_force": 100}})"});
  EXPECT_EQ(session.device.type, "toy-line");
  const RunStats stats = session::MakeEngine(session)->Run(nullptr);

  EXPECT_EQ(stats.method, "toy-plane");
  EXPECT_EQ(stats.ticks, 2000);
  // The largest force is the last tick's: the grip at x = 0.1 m puts the 0.02 m sphere 0.07 m
  // into the wall at 0.05 m, pushed back by k·d = 1000 N/m · 0.07 m (no ramp in this session;
  // within 1 ms of travel).
  EXPECT_NEAR(stats.max_force, 70.0, 0.1);
  // The wall is reached at x = 0.03 m, 0.6 s into the 2 s slide: 1400 of the 2000 ticks.
  ASSERT_EQ(stats.method_status.size(), 1u);
  EXPECT_EQ(stats.method_status[0].first, "toy_plane.penetrating");
  EXPECT_NEAR(static_cast<double>(stats.method_status[0].second), 1400.0, 2.0);
}

TEST(ToyMethodTest, ToyLineDeviceSlidesAlongX) {
  toy::LineDevice line(Vec3::Zero(), Vec3(0.1, 0.0, 0.0), 2.0, device::Specifications{});
  EXPECT_NEAR(line.Read(1.0).X_DT.p.x(), 0.05, 1e-12);
  EXPECT_NEAR(line.Read(1.0).V_DT.v.x(), 0.05, 1e-12);
  EXPECT_NEAR(line.Read(3.0).X_DT.p.x(), 0.1, 1e-12);
  EXPECT_EQ(line.Read(3.0).V_DT.v.x(), 0.0);
}

}  // namespace
}  // namespace mrh::engine::testing
