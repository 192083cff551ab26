// SPDX-License-Identifier: Apache-2.0
// Tests of WriteSummary: summary.json parses and carries every RunStats field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "mrh/core/error.h"
#include "mrh/report/report.h"
#include "report/report_test_util.h"

namespace mrh::report {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using testing::ReadText;
using testing::TempDir;
using ::testing::ThrowsMessage;

// Distinct values per field, so a field written under the wrong key is caught.
engine::RunStats MakeStats() {
  engine::RunStats s;
  s.method = "impulse";
  s.mode = settings::Mode::kRealtime;
  s.physics_dt = 0.05;
  s.haptic_dt = 0.001;
  s.sim_time = 10.0;
  s.wall_time = 10.5;
  s.ticks = 10000;
  s.steps = 200;
  s.haptic_rate_hz = 999.5;
  s.physics_rate_hz = 19.9;
  s.overruns = 3;
  s.jitter_p50_us = 1.5;
  s.jitter_p99_us = 40.0;
  s.jitter_max_us = 900.0;
  s.step_ms_p50 = 0.2;
  s.step_ms_p99 = 1.1;
  s.step_ms_max = 4.5;
  s.max_force = 12.5;
  s.max_torque = 0.75;
  s.fault_nonfinite_wrench = 11;
  s.fault_nonfinite_device = 12;
  s.force_clamped = 13;
  s.torque_clamped = 14;
  s.watchdog_ticks = 15;
  s.dropped_tick_records = 16;
  s.dropped_reports = 17;
  s.ir_status = 0x5u;
  s.realtime_priority = true;
  s.impulses.push_back(physics::BodyImpulseTotal{
      .body = 2, .name = "cube", .linear = Vec3(3.0, 4.0, 0.0), .angular = Vec3(0.0, 0.0, 1.0)});
  s.warnings = {"SCHED_FIFO refused"};
  return s;
}

json WriteAndRead(const TempDir& dir, const engine::RunStats& stats) {
  WriteSummary(dir.path(), stats, "sessions/a.json", "scenes/b.xml");
  return json::parse(ReadText(dir.path() / "summary.json"));
}

TEST(SummaryTest, HoldsRunIdentityAndTiming) {
  const TempDir dir;
  const json j = WriteAndRead(dir, MakeStats());
  EXPECT_EQ(j.at("session"), "sessions/a.json");
  EXPECT_EQ(j.at("scene"), "scenes/b.xml");
  EXPECT_EQ(j.at("method"), "impulse");
  EXPECT_EQ(j.at("mode"), "realtime");
  EXPECT_EQ(j.at("physics_dt").get<double>(), 0.05);
  EXPECT_EQ(j.at("haptic_dt").get<double>(), 0.001);
  EXPECT_EQ(j.at("sim_time").get<double>(), 10.0);
  EXPECT_EQ(j.at("wall_time").get<double>(), 10.5);
  EXPECT_EQ(j.at("ticks").get<std::int64_t>(), 10000);
  EXPECT_EQ(j.at("steps").get<std::int64_t>(), 200);
  EXPECT_EQ(j.at("haptic_rate_hz").get<double>(), 999.5);
  EXPECT_EQ(j.at("physics_rate_hz").get<double>(), 19.9);
  EXPECT_EQ(j.at("overruns").get<std::int64_t>(), 3);
  EXPECT_EQ(j.at("realtime_priority").get<bool>(), true);
}

TEST(SummaryTest, HoldsJitterStepTimeAndMaxima) {
  const TempDir dir;
  const json j = WriteAndRead(dir, MakeStats());
  EXPECT_EQ(j.at("jitter_us").at("p50").get<double>(), 1.5);
  EXPECT_EQ(j.at("jitter_us").at("p99").get<double>(), 40.0);
  EXPECT_EQ(j.at("jitter_us").at("max").get<double>(), 900.0);
  EXPECT_EQ(j.at("step_ms").at("p50").get<double>(), 0.2);
  EXPECT_EQ(j.at("step_ms").at("p99").get<double>(), 1.1);
  EXPECT_EQ(j.at("step_ms").at("max").get<double>(), 4.5);
  EXPECT_EQ(j.at("max_force").get<double>(), 12.5);
  EXPECT_EQ(j.at("max_torque").get<double>(), 0.75);
}

TEST(SummaryTest, HoldsEveryFaultCounter) {
  const TempDir dir;
  const json f = WriteAndRead(dir, MakeStats()).at("faults");
  EXPECT_EQ(f.at("nonfinite_wrench").get<std::int64_t>(), 11);
  EXPECT_EQ(f.at("nonfinite_device").get<std::int64_t>(), 12);
  EXPECT_EQ(f.at("force_clamped").get<std::int64_t>(), 13);
  EXPECT_EQ(f.at("torque_clamped").get<std::int64_t>(), 14);
  EXPECT_EQ(f.at("watchdog_ticks").get<std::int64_t>(), 15);
  EXPECT_EQ(f.at("dropped_tick_records").get<std::int64_t>(), 16);
  EXPECT_EQ(f.at("dropped_reports").get<std::int64_t>(), 17);
  EXPECT_EQ(f.at("ir_status").get<std::uint32_t>(), 0x5u);
}

// The device's own counters (network packets, vendor errors) are in the
// summary, not only on stdout.
TEST(SummaryTest, HoldsTheDeviceCounters) {
  const TempDir dir;
  engine::RunStats stats = MakeStats();
  stats.device = device::DeviceCounters{.vendor_errors = 1,
                                        .torque_dropped = 2,
                                        .packets_malformed = 3,
                                        .pose_timeouts = 4,
                                        .poses_received = 5,
                                        .wrenches_sent = 6};
  const json d = WriteAndRead(dir, stats).at("device");
  EXPECT_EQ(d.at("vendor_errors").get<std::int64_t>(), 1);
  EXPECT_EQ(d.at("torque_dropped").get<std::int64_t>(), 2);
  EXPECT_EQ(d.at("packets_malformed").get<std::int64_t>(), 3);
  EXPECT_EQ(d.at("pose_timeouts").get<std::int64_t>(), 4);
  EXPECT_EQ(d.at("poses_received").get<std::int64_t>(), 5);
  EXPECT_EQ(d.at("wrenches_sent").get<std::int64_t>(), 6);
  EXPECT_EQ(d.size(), 6u);
}

TEST(SummaryTest, HoldsImpulsesWithNormAndWarnings) {
  const TempDir dir;
  const json j = WriteAndRead(dir, MakeStats());
  ASSERT_EQ(j.at("impulses").size(), 1u);
  const json& impulse = j.at("impulses")[0];
  EXPECT_EQ(impulse.at("body").get<int>(), 2);
  EXPECT_EQ(impulse.at("name"), "cube");
  EXPECT_EQ(impulse.at("linear"), json::array({3.0, 4.0, 0.0}));
  EXPECT_EQ(impulse.at("angular"), json::array({0.0, 0.0, 1.0}));
  // |(3, 4, 0)| = 5 exactly in floating point.
  EXPECT_EQ(impulse.at("linear_norm").get<double>(), 5.0);
  EXPECT_EQ(j.at("warnings"), json::array({"SCHED_FIFO refused"}));
}

TEST(SummaryTest, LockstepModeAndEmptyListsAreWritten) {
  const TempDir dir;
  const json j = WriteAndRead(dir, engine::RunStats{});
  EXPECT_EQ(j.at("mode"), "lockstep");
  EXPECT_TRUE(j.at("impulses").is_array());
  EXPECT_TRUE(j.at("impulses").empty());
  EXPECT_TRUE(j.at("warnings").is_array());
}

TEST(SummaryTest, UnwritableFolderThrowsNamingThePath) {
  const TempDir dir;
  const std::filesystem::path blocker = dir.path() / "blocker";
  std::ofstream(blocker) << "x";
  EXPECT_THAT(
      [&] {
        WriteSummary(blocker / "run", engine::RunStats{}, "s.json", "w.xml");
      },
      ThrowsMessage<RuntimeError>(HasSubstr((blocker / "run").string())));
}

}  // namespace
}  // namespace mrh::report
