// SPDX-License-Identifier: Apache-2.0
// Sessions with the hardware and network devices: their keys, device models and limits, the
// stiffness limit, and a lockstep run through the fake libdhd.so whose recorded forces must
// equal the displayed wrench in the device frame.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "mrh/engine/engine.h"
#include "mrh/world/world.h"
#include "session/session_test_util.h"
#include "tests/device/fake_library.h"

namespace mrh::session {
namespace {

using testing::Parse;
using testing::ThrowsInvalid;
using testing::WithDevice;

TEST(HardwareSessionTest, ForceDimensionTakesALibrarySonameOrAnExistingPath) {
  EXPECT_EQ(Parse(WithDevice(R"({"type": "forcedimension"})")).device.forcedimension.library,
            "libdhd.so");
  EXPECT_EQ(Parse(WithDevice(R"({"type": "forcedimension", "library": "libdhd.so.3"})"))
                .device.forcedimension.library,
            "libdhd.so.3");
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "forcedimension", "library": "sdk/libdhd.so"})"));
      },
      ThrowsInvalid("session.json: device.library:"));
}

TEST(HardwareSessionTest, OpenHapticsTakesALibraryAndADeviceName) {
  const Session s = Parse(WithDevice(R"({"type": "openhaptics", "name": "Left Device"})"));
  EXPECT_EQ(s.device.openhaptics.library, "libHD.so");
  EXPECT_EQ(s.device.openhaptics.name, "Left Device");
}

TEST(HardwareSessionTest, UdpReadsBindTimeoutAndFade) {
  const Session s = Parse(
      WithDevice(R"({"type": "udp", "bind": "0.0.0.0:50000", "timeout": 0.1, "fade": 0.02})"));
  EXPECT_EQ(s.device.udp.bind, "0.0.0.0:50000");
  EXPECT_EQ(s.device.udp.timeout, 0.1);
  EXPECT_EQ(s.device.udp.fade, 0.02);
  EXPECT_EQ(Parse(WithDevice(R"({"type": "udp"})")).device.udp.bind, "127.0.0.1:47800");
}

TEST(HardwareSessionTest, BadUdpValuesAreOneLineErrorsNamingTheKey) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "udp", "bind": "localhost"})"));
      },
      ThrowsInvalid("session.json: device.bind: \"localhost\" is not host:port"));
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "udp", "timeout": 0})"));
      },
      ThrowsInvalid("session.json: device.timeout: 0 s; expected a number > 0"));
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "forcedimension", "bind": "1.2.3.4:5"})"));
      },
      ThrowsInvalid("device.bind: not used by device type \"forcedimension\""));
}

TEST(HardwareSessionTest, AModelBringsItsDataSheetLimitsAndLimitsOverrideThem) {
  const Session touch = Parse(WithDevice(R"({"type": "udp", "model": "touch"})"));
  EXPECT_EQ(touch.device.specs.max_force, 3.3);
  EXPECT_FALSE(touch.device.specs.has_torque);
  const Session raised = Parse(WithDevice(
      R"({"type": "udp", "model": "touch", "limits": {"max_force": 2, "output_dof": 6,
          "workspace_radius": 0.1}})"));
  EXPECT_EQ(raised.device.specs.max_force, 2.0);
  EXPECT_EQ(raised.device.specs.max_stiffness, 1020.0);  // kept from the model
  EXPECT_TRUE(raised.device.specs.has_torque);
  EXPECT_EQ(raised.device.specs.workspace_max, Vec3::Constant(0.1));
}

TEST(HardwareSessionTest, UnknownModelsAndBadDofAreErrors) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "udp", "model": "omega"})"));
      },
      ThrowsInvalid("session.json: device.model: unknown device model \"omega\"; "
                    "expected one of \"touch\""));
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "udp", "limits": {"output_dof": 4}})"));
      },
      ThrowsInvalid("device.limits.output_dof: 4; expected 3 (force only) or 6"));
}

TEST(HardwareSessionTest, StiffnessAboveAStatedLimitNamesBothKeysAndValues) {
  const std::string text = R"({"scene": "scene.xml", "rendering": {"stiffness": 2000},
      "device": {"type": "udp", "model": "touch"}})";
  EXPECT_THAT(
      [&] {
        Parse(text);
      },
      ThrowsInvalid("session.json: rendering.stiffness: rendering.stiffness = 2000 N/m "
                    "exceeds device.limits.max_stiffness = 1020 N/m (device.model "
                    "\"touch\"); expected rendering.stiffness <= "
                    "device.limits.max_stiffness, or raise"));
  // The user may raise the limit explicitly.
  EXPECT_NO_THROW(Parse(text, {"device.limits.max_stiffness=2500"}));
  // Without a model or an explicit limit no device maximum is known: no check.
  EXPECT_NO_THROW(Parse(R"({"scene": "scene.xml", "rendering": {"stiffness": 9000},
      "device": {"type": "udp"}})"));
}

class TickForces final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& t) override { displayed_W.push_back(t.displayed_W); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<Wrench> displayed_W;
};

// The pointer (r = 1 cm) presses 5 mm into the free box's -x face (x = 0.15 m) in zero gravity,
// held by the fake DHD; the device frame is turned 90 degrees about z against the world.
TEST(HardwareSessionTest, ForcesWrittenToTheDhdEqualTheDisplayedWrenchInTheDeviceFrame) {
  device::testing::FakeLibrary fake(MRH_FAKE_DHD);
  fake.Get<void()>("fakedhd_Reset")();
  const double s = std::sqrt(0.5);
  const Quat q_WD(s, 0, 0, s);
  const Vec3 p_D = q_WD.conjugate() * Vec3(0.045, 0, 0);  // p_W = (0.1,0,0) + R p_D = (0.145,0,0)
  const double p[3] = {p_D.x(), p_D.y(), p_D.z()}, R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double v[3] = {0, 0, 0};
  fake.Get<void(const double*, const double*, const double*, int)>("fakedhd_SetPose")(p, R, v, 0);
  const Session session = Parse(std::string(R"({"scene": "scene.xml", "gravity": [0, 0, 0],
      "duration": 0.2, "safety": {"ramp": false},
      "device": {"type": "forcedimension", "library": ")") +
                                MRH_FAKE_DHD + R"(",
        "calibration": {"position": [0.1, 0, 0], "orientation": [)" +
                                std::to_string(s) + ", 0, 0, " + std::to_string(s) + "]}}}");
  TickForces recorder;
  const engine::RunStats stats = MakeEngine(session)->Run(&recorder);
  ASSERT_GT(stats.ticks, 0);

  const auto count = fake.Get<int()>("fakedhd_ForceCount")();
  // Open writes a zero, then one write per tick, then zeros as the run stops and Close.
  ASSERT_GE(count, static_cast<int>(recorder.displayed_W.size()) + 2);
  std::array<double, 6> last{};
  fake.Get<void(int, double*)>("fakedhd_Force")(count - 1, last.data());
  EXPECT_EQ(Vec3(last[0], last[1], last[2]), Vec3::Zero());
  const Quat q = session.device.calibration.X_WD.q;
  int pushing = 0;
  for (std::size_t i = 0; i < recorder.displayed_W.size(); ++i) {
    std::array<double, 6> f{};
    fake.Get<void(int, double*)>("fakedhd_Force")(static_cast<int>(i) + 1, f.data());
    const Vec3 f_D = q.conjugate() * recorder.displayed_W[i].f;
    EXPECT_NEAR((Vec3(f[0], f[1], f[2]) - f_D).norm(), 0.0, 1e-12) << "tick " << i;
    if (recorder.displayed_W[i].f.x() < 0.0) ++pushing;
  }
  EXPECT_GT(pushing, 0);  // the box pushes the pointer back along -x_W, i.e. +y_D
  EXPECT_EQ(fake.Get<int()>("fakedhd_IsOpen")(), 0);
}

// Lockstep never waits for a real device (8 s of simulation in 0.02 s, no packet
// answered). A real device's session runs in real time unless it names a mode; "lockstep" is
// refused naming the mode to use.
TEST(HardwareSessionTest, RealDevicesRunInRealTimeAndRefuseLockstep) {
  for (const char* type : {"udp", "forcedimension", "openhaptics"}) {
    const std::string device = std::string(R"({"type": ")") + type + "\"}";
    EXPECT_EQ(Parse(WithDevice(device)).engine.mode, settings::Mode::kRealtime) << type;
    const std::string lockstep =
        R"({"scene": "scene.xml", "mode": "lockstep", "device": )" + device + "}";
    EXPECT_THAT(
        [&] {
          (void)Parse(lockstep);
        },
        ThrowsInvalid(std::string("session.json: mode: \"lockstep\" with the real device \"") +
                      type + "\""))
        << type;
  }
  // Simulated devices keep the default, lockstep.
  EXPECT_EQ(Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0]})")).engine.mode,
            settings::Mode::kLockstep);
}

}  // namespace
}  // namespace mrh::session
