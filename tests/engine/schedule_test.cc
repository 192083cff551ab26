// SPDX-License-Identifier: Apache-2.0
// The lockstep scheduler reproduces the timing rule (thesis §4.1.3; docs/architecture.md) exactly.
#include <gtest/gtest.h>

#include <vector>

#include "engine_test_util.h"
#include "mrh/engine/method.h"

namespace mrh::engine::testing {
namespace {

// A probe method: records which snapshot each tick renders and which period each step consumes.
struct ProbeLog {
  std::vector<std::int64_t> tick_snapshot;  // per tick: snapshot step adopted
  std::vector<int> tick_j;
  std::vector<std::int64_t> step_input_period;  // per step: newest period in its report
};

class ProbePhysics final : public physics::MethodPhysics {
 public:
  explicit ProbePhysics(ProbeLog* log) : log_(log) {}

  void PhysicsStart(const ir::HapticReport&, ir::PhysicsSnapshot* out) override { out->step = -1; }

  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot*) override {
    log_->step_input_period.push_back(report.period);
  }

 private:
  ProbeLog* log_;
};

class ProbeHaptic final : public haptic::MethodHaptic {
 public:
  explicit ProbeHaptic(ProbeLog* log) : log_(log) {}

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override { step_ = snapshot.step; }

  void HapticTick(const haptic::TickInput& in, haptic::TickOutput*) noexcept override {
    log_->tick_snapshot.push_back(step_);
    log_->tick_j.push_back(in.j);
  }

  void EndPeriod(ir::HapticReport*) noexcept override {}

 private:
  ProbeLog* log_;
  std::int64_t step_ = -2;
};

ProbeLog* g_log = nullptr;

TEST(ScheduleTest, PeriodKRendersStepKMinus1AndStepKConsumesPeriodKMinus1) {
  ProbeLog log;
  g_log = &log;
  RegisterMethod("probe", "test probe", [](const physics::MethodContext&) {
    return Method{"probe",
                  false,
                  std::make_unique<ProbePhysics>(g_log),
                  std::make_unique<ProbeHaptic>(g_log),
                  {}};
  });
  settings::EngineSettings s = T41Settings("probe");
  s.physics_dt = 0.005;
  s.duration = 0.05;  // 10 periods of n = 5 ticks
  auto engine = T41Engine(s);
  const RunStats stats = engine->Run(nullptr);
  const int n = 5;
  ASSERT_EQ(stats.ticks, 50);
  ASSERT_EQ(log.tick_snapshot.size(), 50u);
  for (std::size_t tick = 0; tick < log.tick_snapshot.size(); ++tick) {
    const auto k = static_cast<std::int64_t>(tick) / n;
    EXPECT_EQ(log.tick_snapshot[tick], k - 1) << "tick " << tick;
    EXPECT_EQ(log.tick_j[tick], static_cast<int>(tick) % n) << "tick " << tick;
  }
  ASSERT_EQ(log.step_input_period.size(), 10u);
  for (std::size_t k = 0; k < log.step_input_period.size(); ++k) {
    EXPECT_EQ(log.step_input_period[k], static_cast<std::int64_t>(k) - 1) << "step " << k;
  }
}

// Asks the engine to stop from inside the run, after the physics step numbered `at`.
class StopAfterStep final : public physics::Recorder {
 public:
  StopAfterStep(Engine* engine, std::int64_t at) : engine_(engine), at_(at) {}

  void OnTick(const ir::TickRecord&) override { ++ticks; }

  void OnStep(const physics::StepRecord& step, const world::World&) override {
    if (step.step == at_) engine_->RequestStop();
  }

  std::int64_t ticks = 0;

 private:
  Engine* engine_;
  std::int64_t at_;
};

TEST(ScheduleTest, RequestStopEndsALockstepRunBeforeItsNextPeriod) {
  const settings::EngineSettings s = T41Settings("impulse");  // 50 ticks per 50 ms step, 2.5 s
  auto engine = T41Engine(s);
  StopAfterStep recorder(engine.get(), 2);
  const RunStats stats = engine->Run(&recorder);
  EXPECT_EQ(stats.ticks, 150);  // periods 0, 1 and 2
  EXPECT_EQ(recorder.ticks, 150);
  EXPECT_DOUBLE_EQ(stats.sim_time, 0.15);
}

TEST(ScheduleTest, RequestStopBeforeRunEndsItAtOnce) {
  auto engine = T41Engine(T41Settings("impulse"));
  engine->RequestStop();
  const RunStats stats = engine->Run(nullptr);
  EXPECT_EQ(stats.ticks, 0);
}

}  // namespace
}  // namespace mrh::engine::testing
