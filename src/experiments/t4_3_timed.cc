// SPDX-License-Identifier: Apache-2.0
// The "timed:<method>" wrapper (RegisterTimedMethod): per-call wall and CPU times of a method's
// halves, for the occupancy (t4.3) and tick-cost (t4.5) experiments.
#include <chrono>
#include <ctime>
#include <memory>
#include <vector>

#include "experiments_impl.h"
#include "mrh/engine/method.h"
#include "mrh/haptic/method_haptic.h"

namespace mrh::experiments::internal {
namespace {

using Clock = std::chrono::steady_clock;

double Us(Clock::time_point t0) noexcept {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

double ThreadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

// Appends within the reserved capacity only, so the haptic half never allocates.
void Keep(std::vector<double>* v, double value, std::size_t cap) noexcept {
  if (v->size() < v->capacity() && v->size() < cap) v->push_back(value);
}

// Forwards to an inner method's physics half and records how long each step took (see
// RegisterTimedMethod).
class TimedPhysics final : public physics::MethodPhysics {
 public:
  TimedPhysics(std::unique_ptr<physics::MethodPhysics> inner, std::shared_ptr<MethodTimings> sink)
      : inner_(std::move(inner)), sink_(std::move(sink)) {}

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override {
    inner_->PhysicsStart(initial, out);
  }

  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override {
    const double cpu0 = ThreadCpuMs();
    const auto t0 = Clock::now();
    inner_->PhysicsStep(report, out);
    const auto t1 = Clock::now();
    sink_->step_cpu_ms.push_back(ThreadCpuMs() - cpu0);
    sink_->step_wall_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (sink_->on_snapshot) sink_->on_snapshot(*out);
    if (sink_->on_step) sink_->on_step(*inner_);
  }

 private:
  std::unique_ptr<physics::MethodPhysics> inner_;
  std::shared_ptr<MethodTimings> sink_;
};

// Forwards to an inner method's haptic half and records how long each call took, into buffers
// reserved here (the haptic half never allocates).
class TimedHaptic final : public haptic::MethodHaptic {
 public:
  TimedHaptic(std::unique_ptr<haptic::MethodHaptic> inner, std::shared_ptr<MethodTimings> sink,
              std::size_t max_ticks, std::size_t max_steps)
      : inner_(std::move(inner)),
        sink_(std::move(sink)),
        max_ticks_(max_ticks),
        max_steps_(max_steps) {
    sink_->tick_wall_us.reserve(sink_->tick_wall_us.size() + max_ticks);
    sink_->tick_j.reserve(sink_->tick_j.size() + max_ticks);
    sink_->tick_contacts.reserve(sink_->tick_contacts.size() + max_ticks);
    sink_->adopt_wall_us.reserve(sink_->adopt_wall_us.size() + max_steps + 1);
    sink_->end_period_wall_us.reserve(sink_->end_period_wall_us.size() + max_steps + 1);
  }

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override {
    const auto t0 = Clock::now();
    inner_->Adopt(snapshot);
    Keep(&sink_->adopt_wall_us, Us(t0), max_steps_ + 1);
  }

  void HapticTick(const haptic::TickInput& in, haptic::TickOutput* out) noexcept override {
    const auto t0 = Clock::now();
    inner_->HapticTick(in, out);
    const double us = Us(t0);
    if (ticks_++ >= max_ticks_) return;
    sink_->tick_wall_us.push_back(us);
    sink_->tick_j.push_back(in.j);
    sink_->tick_contacts.push_back(out->contacts);
  }

  void EndPeriod(ir::HapticReport* report) noexcept override {
    const auto t0 = Clock::now();
    inner_->EndPeriod(report);
    Keep(&sink_->end_period_wall_us, Us(t0), max_steps_ + 1);
  }

 private:
  std::unique_ptr<haptic::MethodHaptic> inner_;
  std::shared_ptr<MethodTimings> sink_;
  std::size_t max_ticks_, max_steps_;
  std::size_t ticks_ = 0;
};

}  // namespace

std::string RegisterTimedMethod(const std::string& inner, std::shared_ptr<MethodTimings> sink,
                                std::size_t max_ticks, std::size_t max_steps) {
  const std::string name = "timed:" + inner;
  engine::RegisterMethod(
      name, "experiments: " + inner + " with per-call timing",
      [inner, sink, max_ticks, max_steps](const physics::MethodContext& context) {
        engine::Method m = engine::MakeMethod(inner, context);
        m.physics = std::make_unique<TimedPhysics>(std::move(m.physics), sink);
        m.haptic = std::make_unique<TimedHaptic>(std::move(m.haptic), sink, max_ticks, max_steps);
        return m;
      });
  return name;
}

}  // namespace mrh::experiments::internal
