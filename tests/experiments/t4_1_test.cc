// SPDX-License-Identifier: Apache-2.0
// The T4.1 driver reproduces the thesis' essential result and writes its artefacts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "mrh/core/error.h"
#include "mrh/experiments/experiments.h"

namespace mrh::experiments {
namespace {

TEST(T41ExperimentTest, SingleRateIsElasticAndImpulseMethodOvershoots) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "mrh_experiments_test_t4_1";
  std::filesystem::remove_all(out);
  ASSERT_EQ(experiments::Run("t4.1", out, /*quiet=*/true), 0);
  for (const char* file : {"force_time.csv", "impulse_table.csv", "impulse_table.md",
                           "summary.json", "single-rate/ticks.csv", "impulse/summary.json"}) {
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  }
  std::ifstream in(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  const double single = summary["methods"]["single-rate"]["impulse_Ns"];
  const double impulse = summary["methods"]["impulse"]["impulse_Ns"];
  // Analytic: an undamped bounce returns 2mv = 2.04 N·s (SPEC T4.1).
  EXPECT_NEAR(single, 2.04, 0.02 * 2.04);
  EXPECT_GT(impulse, 1.2 * single);
  std::filesystem::remove_all(out);
}

TEST(T41ExperimentTest, UnknownExperimentListsKnownOnes) {
  EXPECT_THAT([] { experiments::Run("t9.9", "/tmp/unused", true); },
              ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("t4.1")));
}

}  // namespace
}  // namespace mrh::experiments
