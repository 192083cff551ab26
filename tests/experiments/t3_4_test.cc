// SPDX-License-Identifier: Apache-2.0
// The T3.4 driver renders an N-gon prism with N contact points (timings are not checked; contact
// counts, convergence and the analytic sliding force are).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "experiments/experiments_impl.h"

namespace mrh::experiments {
namespace {

TEST(T34ExperimentTest, PrismBaseGivesOneContactPerSideAndAFrictionRowEach) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "mrh_experiments_test_t3_4";
  std::filesystem::remove_all(out);
  internal::T34Options options;
  options.sides = {5, 100, 1000};
  options.duration = 0.06;  // three physics steps; the first is not counted
  ASSERT_EQ(internal::RunT34(out, /*quiet=*/true, options), 0);
  std::ifstream in(out / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  ASSERT_EQ(s["runs"].size(), 6u);
  for (const auto& [name, pass] : s["checks"].items()) EXPECT_TRUE(pass.get<bool>()) << name;
  for (const nlohmann::json& run : s["runs"]) {
    const int sides = run["sides"].get<int>();
    EXPECT_EQ(run["contacts"].get<int>(), sides);
    EXPECT_EQ(run["rows"].get<int>(), run["friction"].get<bool>() ? 2 * sides : sides);
    EXPECT_GT(run["p50_us"].get<double>(), 0.0);
    EXPECT_EQ(run["unconverged_ticks"].get<int>(), 0) << sides;
    EXPECT_LT(run["force_error_N"].get<double>(), 9000.0 * 1e-8) << sides;  // k_t × 1e-8 m
  }
  EXPECT_TRUE(std::filesystem::exists(out / "t3_4.csv"));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace mrh::experiments
