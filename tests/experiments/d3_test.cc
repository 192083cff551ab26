// SPDX-License-Identifier: Apache-2.0
// D3: each material's contact transient is fitted back from the rendered force, and its
// stiffness is what the pointer feels at rest.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

class D3ExperimentTest : public testing::ExperimentTest<D3ExperimentTest> {
 protected:
  static void SetUpTestSuite() {
    RunExperiment("mrh_experiments_test_d3_", [](const std::filesystem::path& out) {
      return RunD3(out, /*quiet=*/true);
    });
  }
};

TEST_F(D3ExperimentTest, PassesItsChecks) {
  EXPECT_EQ(exit_code_, 0);
  testing::ExpectAllChecksPass(*summary_);
  EXPECT_TRUE(std::filesystem::exists(*out_ / "d3.csv"));
}

// The fit knows nothing of the session; its results must come back to the session's values.
TEST_F(D3ExperimentTest, FitRecoversTheSessionsMaterialsAtEverySpeed) {
  const nlohmann::json& fits = (*summary_)["fits"];
  ASSERT_EQ(fits.size(), 9u);  // three materials × three speeds
  for (const nlohmann::json& row : fits) {
    const double f = row["f_hz"], b = row["decay_1_s"], av = row["a_v_n"];
    EXPECT_NEAR(row["f_fit_hz"].get<double>(), f, 0.05 * f) << row.dump();
    EXPECT_NEAR(row["decay_fit_1_s"].get<double>(), b, 0.25 * b) << row.dump();
    EXPECT_NEAR(row["a_v_fit_n"].get<double>(), av, 0.15 * av) << row.dump();
    const double k = row["stiffness_n_m"];
    EXPECT_NEAR(row["stiffness_rest_n_m"].get<double>(), k, 0.01 * k) << row.dump();
  }
}

}  // namespace
}  // namespace mrh::experiments::internal
