// SPDX-License-Identifier: Apache-2.0
// A hand sweeping a row of ordinary objects (scenes/soak_row.json: a box, a ball, an upright
// capsule that tips over, a box) at 0.28 m/s under the methods that simulate the touched bodies
// locally at 20 ms. No body may leave faster than a hit by the hand allows (2.5 × its speed,
// the bar the single-rate reference at 1 ms meets with 0.49 m/s), nor spin faster than such a
// body rolls (2.5 × that speed over the smallest radius, 0.025 m).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kHandSpeed = 1.4 / 5.0;  // m/s, the sweep's keyframes
constexpr double kMaxSpeed = 2.5 * kHandSpeed;
constexpr double kMaxSpin = kMaxSpeed / 0.025;

struct Peak {
  double speed = 0.0;
  double spin = 0.0;
};

class PeakRecorder final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord&) override {}

  void OnStep(const physics::StepRecord&, const world::World& world) override {
    for (int b = 0; b < world.num_bodies(); ++b) {
      const world::BodyInfo& info = world.body(b);
      if (info.is_static || info.is_mocap) continue;
      const world::BodyState s = world.body_state(b);
      Peak& p = peaks[info.name];
      p.speed = std::max(p.speed, s.V_WCm.v.norm());
      p.spin = std::max(p.spin, s.V_WCm.w.norm());
    }
  }

  std::map<std::string, Peak> peaks;
};

class SoakRowTest : public ::testing::TestWithParam<std::string> {};

TEST_P(SoakRowTest, NothingIsThrown) {
  const session::Session session = session::LoadSession(
      std::string(MRH_SOURCE_DIR) + "/scenes/soak_row.json", {"method=" + GetParam()});
  PeakRecorder record;
  session::MakeEngine(session)->Run(&record);
  ASSERT_EQ(record.peaks.size(), 4u);
  for (const auto& [name, peak] : record.peaks) {
    EXPECT_LT(peak.speed, kMaxSpeed) << name << " is thrown";
    EXPECT_LT(peak.spin, kMaxSpin) << name << " is spun";
  }
  EXPECT_GT(record.peaks.at("o0").speed, 0.5 * kHandSpeed) << "the hand missed the row";
}

INSTANTIATE_TEST_SUITE_P(LocalMethods, SoakRowTest,
                         ::testing::Values("local-dynamics", "local-dynamics-6dof", "proxy-6dof"),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string name = p.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace mrh::engine
