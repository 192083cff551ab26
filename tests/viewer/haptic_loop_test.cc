// SPDX-License-Identifier: Apache-2.0
// Tests of the viewer's haptic thread: it ticks, pauses, steps N ticks, resumes, and forgets
// step requests across pauses.
#include "viewer/haptic_loop.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <thread>

#include "mrh/device/external.h"
#include "mrh/world/world.h"

namespace mrh::viewer::internal {
namespace {

// How long a test waits for the haptic thread before it gives up. A bound on a stalled machine,
// not a timing assumption: each wait ends as soon as its condition holds.
constexpr auto kPatience = std::chrono::seconds(30);
constexpr double kDt = 0.001;  // s
// Held periods a test watches to see that nothing runs during a pause (~50 ms at 1 kHz).
constexpr std::int64_t kWatchPeriods = 50;

bool WaitFor(const std::function<bool()>& condition) {
  const auto give_up = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < give_up) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return condition();
}

// The input device: a fixed pose; it remembers the virtual time of the last reading.
class FixedSource final : public device::Device {
 public:
  const device::Specifications& specifications() const override { return specs_; }

  device::DeviceState Read(double t) noexcept override {
    last_t_.store(t);
    device::DeviceState s;
    s.t = t;
    s.X_DT = Pose{Vec3(0.0, 0.0, 0.3), Quat::Identity()};
    return s;
  }

  void SetWrench(const Wrench&) noexcept override {}

  double last_t() const { return last_t_.load(); }

 private:
  device::Specifications specs_;
  std::atomic<double> last_t_{-1.0};
};

constexpr char kScene[] = R"(
<mujoco>
  <option timestep="0.02"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="cube" pos="0 0 0.05"><freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
    <body name="pointer" mocap="true" pos="0 0 0.3">
      <geom type="sphere" size="0.02" contype="0" conaffinity="0"/></body>
  </worldbody>
</mujoco>)";

class HapticLoopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    settings::EngineSettings s;
    s.method = "impulse";
    s.mode = settings::Mode::kRealtime;
    s.physics_dt = 0.02;
    s.haptic_dt = kDt;
    s.realtime_priority = false;
    // As LiveSession does: the first IR is built around the input's first reading.
    auto external = std::make_unique<device::ExternalDevice>();
    external->Feed(source_.Read(0.0));
    engine_ = std::make_unique<engine::Engine>(world::World::LoadString(kScene),
                                               std::move(external), device::Calibration{}, s);
    engine_->Start();
    loop_.Start(engine_.get(), &source_, kDt, false);
  }

  void TearDown() override {
    loop_.Stop();
    (void)engine_->Stop();
  }

  // Pauses and waits until the haptic thread holds: no tick is in flight after this.
  void PauseAndSettle() {
    loop_.set_paused(true);
    const std::int64_t held = loop_.held_periods();
    ASSERT_TRUE(WaitFor([&] {
      return loop_.held_periods() > held + 1;
    }));
  }

  // Waits kWatchPeriods held periods and returns the ticks run meanwhile.
  std::int64_t TicksWhileWatching() {
    const std::int64_t ticks = loop_.ticks();
    const std::int64_t held = loop_.held_periods();
    EXPECT_TRUE(WaitFor([&] {
      return loop_.held_periods() >= held + kWatchPeriods;
    }));
    return loop_.ticks() - ticks;
  }

  FixedSource source_;
  std::unique_ptr<engine::Engine> engine_;
  HapticLoop loop_;
};

TEST_F(HapticLoopTest, TicksTheEngineOnVirtualTime) {
  ASSERT_TRUE(WaitFor([&] {
    return loop_.ticks() >= 20;
  }));
  // The device is read at t = ticks · dt, whatever the wall clock did.
  PauseAndSettle();
  const auto ticks = static_cast<double>(loop_.ticks());
  EXPECT_NEAR(source_.last_t(), (ticks - 1.0) * kDt, 1e-9);
}

TEST_F(HapticLoopTest, PauseStopsTheTicks) {
  ASSERT_TRUE(WaitFor([&] {
    return loop_.ticks() >= 5;
  }));
  PauseAndSettle();
  EXPECT_TRUE(loop_.paused());
  EXPECT_EQ(TicksWhileWatching(), 0);
}

TEST_F(HapticLoopTest, StepRunsExactlyTheRequestedTicksThenHolds) {
  PauseAndSettle();
  const std::int64_t before = loop_.ticks();
  loop_.StepTicks(7);
  ASSERT_TRUE(WaitFor([&] {
    return loop_.ticks() >= before + 7;
  }));
  EXPECT_EQ(TicksWhileWatching(), 0);
  EXPECT_EQ(loop_.ticks(), before + 7);
}

TEST_F(HapticLoopTest, ResumeRunsAgain) {
  PauseAndSettle();
  loop_.set_paused(false);
  const std::int64_t before = loop_.ticks();
  EXPECT_TRUE(WaitFor([&] {
    return loop_.ticks() >= before + 20;
  }));
  EXPECT_FALSE(loop_.paused());
}

TEST_F(HapticLoopTest, StepsLeftOverAtResumeDoNotRunInTheNextPause) {
  PauseAndSettle();
  loop_.StepTicks(1'000'000);  // far more than can run before the resume
  loop_.set_paused(false);
  PauseAndSettle();
  EXPECT_EQ(TicksWhileWatching(), 0);
}

TEST_F(HapticLoopTest, StepRequestsWhileRunningAreIgnored) {
  loop_.StepTicks(1'000'000);
  PauseAndSettle();
  EXPECT_EQ(TicksWhileWatching(), 0);
}

// `mrh view --at T` holds the loop at tick T / dt + 1: it must stop exactly there, with the
// device last read at virtual time T, and stay held.
TEST_F(HapticLoopTest, HoldAtTickStopsExactlyAtThatTickAndStays) {
  ASSERT_TRUE(WaitFor([&] {
    return loop_.ticks() >= 5;
  }));
  const std::int64_t hold = loop_.ticks() + 200;
  loop_.HoldAtTick(hold);
  ASSERT_TRUE(WaitFor([&] {
    return loop_.holding();
  }));
  EXPECT_EQ(TicksWhileWatching(), 0);
  EXPECT_EQ(loop_.ticks(), hold);
  EXPECT_NEAR(source_.last_t(), static_cast<double>(hold - 1) * kDt, 1e-9);
  EXPECT_FALSE(loop_.paused());
}

TEST_F(HapticLoopTest, StatsCountTicksAndReportTheWindowRate) {
  // One full window (kWindow ticks) gives a rate; under load it may be below 1 kHz, never 0.
  ASSERT_TRUE(WaitFor([&] {
    return loop_.ReadStats().rate_hz > 0.0;
  }));
  const LoopStats stats = loop_.ReadStats();
  EXPECT_GE(stats.ticks, static_cast<std::int64_t>(HapticLoop::kWindow));
  EXPECT_GT(stats.rate_hz, 0.0);
  EXPECT_LE(stats.jitter_mean_us, stats.jitter_max_us);
  EXPECT_LE(stats.jitter_p99_us, stats.jitter_max_us);
  EXPECT_FALSE(stats.fifo);
}

}  // namespace
}  // namespace mrh::viewer::internal
