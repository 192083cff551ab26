// SPDX-License-Identifier: Apache-2.0
// Demo D1 in lockstep (deterministic): 80 objects load and rest on the table, the hand's sweep
// touches them, none leaves the table or moves faster than the hand and gravity can make it.
// The real-time bars (rate, overruns, step p99) are the experiment's report, not a test: this
// machine's two shared cores stall.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

class D1LockstepTest : public testing::ExperimentTest<D1LockstepTest> {
 protected:
  static void SetUpTestSuite() {
    RunExperiment("mrh_experiments_test_d1_", [](const std::filesystem::path& out) {
      D1Options o;
      o.realtime = false;  // the whole 10 s hand path, in virtual time
      return RunD1(out, /*quiet=*/true, o);
    });
  }

  static const nlohmann::json& d1() { return (*summary_)["d1"]; }
};

TEST_F(D1LockstepTest, EightyObjectsRestUntouched) {
  EXPECT_EQ(d1()["mode"], "lockstep");
  EXPECT_EQ(d1()["objects"].get<int>(), 80);
  EXPECT_LE(d1()["rest_max_displacement_m"].get<double>(), 1e-3);
  EXPECT_LE(d1()["rest_max_speed_m_per_s"].get<double>(), 0.01);
  EXPECT_TRUE((*summary_)["checks"]["rest_untouched"].get<bool>());
}

TEST_F(D1LockstepTest, TheHandTouchesObjectsWithoutWarningsOrFaults) {
  EXPECT_GT(d1()["contact_ticks"].get<int>(), 0);
  EXPECT_GE(d1()["touched_objects"].get<int>(), 4);
  EXPECT_TRUE((*summary_)["checks"]["no_warnings"].get<bool>());
  EXPECT_TRUE((*summary_)["checks"]["no_faults"].get<bool>());
  EXPECT_TRUE(std::filesystem::exists(*out_ / "d1.csv"));
  EXPECT_TRUE(std::filesystem::exists(*out_ / "d1.md"));
}

// The scene, the path and the speed bound are sound: with MuJoCo's own contacts at 1 ms
// (single-rate), every object stays on the table and within the bound.
TEST_F(D1LockstepTest, TheSingleRateReferenceKeepsEveryObjectOnTheTable) {
  EXPECT_EQ(d1()["reference_off_table"].get<int>(), 0) << d1()["reference_first_off_table"];
  EXPECT_LE(d1()["reference_max_body_speed_m_per_s"].get<double>(),
            d1()["reference_speed_bound_m_per_s"].get<double>());
  EXPECT_GT(d1()["reference_max_body_speed_m_per_s"].get<double>(), 0.0);
}

// Under local-dynamics' contact model every object stays on the table and within the bound, as
// under single-rate at 1 ms: a convex mesh tilted on the table keeps rows at its vertices (one
// MuJoCo contact let a roof prism pivot and sink through the table).
// Every check but peak memory, which is the report's (sanitizers inflate it; no test asserts
// memory or time).
TEST_F(D1LockstepTest, PassesItsChecks) {
  const nlohmann::json& checks = (*summary_)["checks"];
  ASSERT_TRUE(checks.is_object() && checks.size() > 1) << checks.dump();
  for (const auto& [name, pass] : checks.items()) {
    if (name == "peak_rss_mb") continue;
    EXPECT_TRUE(pass.is_boolean() && pass.get<bool>()) << name << " = " << pass.dump();
  }
}

TEST_F(D1LockstepTest, NoObjectLeavesTheTable) {
  EXPECT_EQ(d1()["off_table"].get<int>(), 0) << d1()["first_off_table"];
}

// Objects are moved only by the pointer (at most twice its speed, an elastic impact) and by
// gravity over the drops they make on the table.
TEST_F(D1LockstepTest, NoObjectOutrunsTheHandAndGravity) {
  const double v = d1()["max_body_speed_m_per_s"].get<double>();
  EXPECT_LE(v, d1()["speed_bound_m_per_s"].get<double>()) << d1()["fastest_body"];
}

}  // namespace
}  // namespace mrh::experiments::internal
