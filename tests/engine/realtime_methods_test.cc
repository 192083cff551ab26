// SPDX-License-Identifier: Apache-2.0
// Every registered method in real-time mode, on the two threads, pushing a box that rests on a
// floor with friction (scenes/t3_6_push.json): the TSan preset runs this file, so each method's
// physics/haptic data flow (snapshots, reports, the local models' adoption) is checked for
// races, not only the impulse method's. No assertion depends on wall-clock timing: the scripted
// device follows wall time, so the pointer reaches the box (contact at ~1 s) even when the
// physics thread lags, as it may under a sanitizer on a loaded machine.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "mrh/engine/engine.h"
#include "mrh/engine/method.h"
#include "mrh/session/session.h"

namespace mrh::engine {
namespace {

// Every registered method, plus local-dynamics with the thesis' perturbation model.
std::vector<std::string> MethodNames() {
  std::vector<std::string> names;
  for (const auto& [name, summary] : ListMethods()) names.push_back(name);
  names.push_back("local-dynamics:perturbation");
  return names;
}

// "method" or "method:local_model" as session overrides.
std::vector<std::string> Overrides(const std::string& param) {
  const std::size_t colon = param.find(':');
  std::vector<std::string> out{"method=" + param.substr(0, colon), "mode=realtime", "duration=2.5",
                               "realtime_priority=false",
                               "pointer.radius=0.02"};  // 3-DOF methods: a sphere at the pointer
  if (colon != std::string::npos) out.push_back("rendering.local_model=" + param.substr(colon + 1));
  return out;
}

class RealtimeMethodTest : public ::testing::TestWithParam<std::string> {};

TEST_P(RealtimeMethodTest, PushesTheBoxOnTwoThreadsWithoutFaults) {
  const session::Session session = session::LoadSession(
      std::string(MRH_SOURCE_DIR) + "/scenes/t3_6_push.json", Overrides(GetParam()));
  const auto engine = session::MakeEngine(session);
  const RunStats stats = engine->Run(nullptr);
  EXPECT_EQ(stats.mode, settings::Mode::kRealtime);
  EXPECT_GT(stats.ticks, 0);
  EXPECT_GT(stats.steps, 0);
  EXPECT_EQ(stats.fault_nonfinite_wrench, 0);
  EXPECT_EQ(stats.fault_nonfinite_device, 0);
  EXPECT_TRUE(std::isfinite(stats.max_force));
  // In contact from ~1 s: the box's friction is μ m g = 0.5 · 0.5 · 9.81 = 2.45 N.
  EXPECT_GT(stats.max_force, 0.5) << "no contact: " << stats.ticks << " ticks, " << stats.steps
                                  << " steps, " << stats.overruns << " overruns, "
                                  << stats.watchdog_ticks << " watchdog ticks";
}

// "local-dynamics" → "local_dynamics" (test names are identifiers).
std::string TestName(const ::testing::TestParamInfo<std::string>& param) {
  std::string name = param.param;
  for (char& c : name) {
    if (c == '-' || c == ':') c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(AllMethods, RealtimeMethodTest, ::testing::ValuesIn(MethodNames()),
                         TestName);

}  // namespace
}  // namespace mrh::engine
