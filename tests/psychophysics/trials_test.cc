// SPDX-License-Identifier: Apache-2.0
// Trials files: write, read back, strict errors; the analysis files of a set of trials.
#include "mrh/psychophysics/trials.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "mrh/core/error.h"
#include "mrh/psychophysics/analysis.h"

namespace mrh::psychophysics {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path TempDir(const std::string& stem) {
  const fs::path dir = fs::temp_directory_path() / (stem + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TrialRow Row(const std::string& subject, const std::string& method, double mass, bool heavier,
             int trial) {
  return TrialRow{.subject = subject,
                  .trial = trial,
                  .method = method,
                  .standard_method = "single-rate",
                  .standard_mass = 60,
                  .comparison_mass = mass,
                  .speed = 0.017,
                  .comparison_first = true,
                  .answer = heavier ? 1 : 2,
                  .comparison_heavier = heavier,
                  .response_time = 0.25,
                  .seed = 18446744073709551615u};
}

TEST(TrialsTest, RowsRoundTripThroughTheFile) {
  const fs::path dir = TempDir("mrh_trials_roundtrip_");
  {
    TrialsWriter w(dir / "trials.csv");
    w.Append(Row("A", "impulse", 45, true, 0));
  }
  {
    TrialsWriter w(dir / "trials.csv");  // appending: no second header
    w.Append(Row("A", "impulse", 75.5, false, 1));
  }
  const std::vector<TrialRow> rows = ReadTrials(dir / "trials.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].comparison_mass, 75.5);
  EXPECT_FALSE(rows[1].comparison_heavier);
  EXPECT_EQ(rows[0].seed, 18446744073709551615u);
  EXPECT_EQ(rows[0].response_time, 0.25);
  fs::remove_all(dir);
}

std::string ErrorOf(const std::string& text) {
  const fs::path dir = TempDir("mrh_trials_bad_");
  std::ofstream(dir / "t.csv") << text;
  try {
    (void)ReadTrials(dir / "t.csv");
  } catch (const InvalidArgument& e) {
    fs::remove_all(dir);
    return e.what();
  }
  fs::remove_all(dir);
  return "no error";
}

TEST(TrialsTest, BadFilesNameTheLineAndTheColumn) {
  const std::string header = TrialsHeader() + "\n";
  EXPECT_THAT(ErrorOf(""), HasSubstr("t.csv:1: empty file"));
  EXPECT_THAT(ErrorOf("subject,trial\n"), HasSubstr("no column \"method\""));
  EXPECT_THAT(ErrorOf(header + "A,0,impulse,single-rate,60,x,0.017,1,1,1,0.2,5\n"),
              HasSubstr("t.csv:2: column comparison_mass = \"x\""));
  EXPECT_THAT(ErrorOf(header + "A,0,impulse,single-rate,60,45,0.017,1,3,1,0.2,5\n"),
              HasSubstr("column answer = \"3\""));
  EXPECT_THAT(ErrorOf(header + "A,0,impulse,single-rate,60,45,0.017,1,2,1,0.2,5\n"),
              HasSubstr("column comparison_heavier"));
  EXPECT_THAT(ErrorOf(header + "A,0,impulse\n"), HasSubstr("column standard_method"));
}

// Data from another tool holds only what the fit needs, in any order.
TEST(TrialsTest, FiveEssentialColumnsAreEnough) {
  const fs::path dir = TempDir("mrh_trials_five_");
  std::ofstream(dir / "t.csv")
      << "comparison_mass,subject,comparison_heavier,method,standard_mass\n"
         "45,P1,0,impulse,60\n75,P1,1,impulse,60\n";
  const std::vector<TrialRow> rows = ReadTrials(dir / "t.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].subject, "P1");
  EXPECT_EQ(rows[1].method, "impulse");
  EXPECT_EQ(rows[1].standard_mass, 60.0);
  EXPECT_EQ(rows[1].comparison_mass, 75.0);
  EXPECT_TRUE(rows[1].comparison_heavier);
  EXPECT_FALSE(rows[0].comparison_heavier);
  EXPECT_EQ(rows[0].trial, 0);  // the row's index
  EXPECT_EQ(rows[1].trial, 1);
  EXPECT_EQ(rows[1].answer, 2);  // stimulus 2 was the comparison (comparison_first 0)
  EXPECT_EQ(rows[0].answer, 1);
  fs::remove_all(dir);
  EXPECT_THAT(ErrorOf("subject,method,standard_mass,comparison_mass\n"),
              HasSubstr("no column \"comparison_heavier\"; expected at least subject"));
}

TEST(AnalysisTest, GroupsBySubjectAndMethodAndWritesExactlyTheDocumentedKeys) {
  std::vector<TrialRow> rows;
  int trial = 0;
  // A: answers rise with mass (fittable); B: always "comparison heavier" (not fittable).
  const int yes[] = {1, 3, 6, 8};
  const double masses[] = {30, 50, 70, 90};
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < 10; ++i) {
      rows.push_back(Row("A", "impulse", masses[k], i < yes[k], trial++));
      rows.push_back(Row("B", "impulse", masses[k], true, trial++));
    }
  }
  const std::vector<SubjectFit> fits = FitAll(rows);
  ASSERT_EQ(fits.size(), 2u);
  EXPECT_EQ(fits[0].subject, "A");
  ASSERT_EQ(fits[0].data.size(), 4u);
  EXPECT_EQ(fits[0].data[2].yes, 6);
  EXPECT_EQ(fits[0].fit.status, FitStatus::kOk);
  EXPECT_EQ(fits[1].fit.status, FitStatus::kAllSame);
  const fs::path dir = TempDir("mrh_analysis_");
  std::string why;
  (void)WriteAnalysis(dir, fits, &why);
  std::ifstream in(dir / "psychometric.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.size(), 1u);
  ASSERT_EQ(j["fits"].size(), 2u);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j["fits"][0].items()) keys.push_back(key);
  EXPECT_THAT(keys,
              ::testing::UnorderedElementsAre("subject", "method", "standard_mass", "trials",
                                              "theta1", "theta2", "pse", "pse_sd", "chi2", "p"));
  EXPECT_DOUBLE_EQ(j["fits"][0]["pse"].get<double>(), fits[0].fit.pse);
  EXPECT_EQ(j["fits"][0]["trials"], 40);
  EXPECT_TRUE(j["fits"][1]["pse"].is_null());
  EXPECT_EQ(j["fits"][1]["trials"], 40);
  std::ifstream md(dir / "pse_table.md");
  std::stringstream table;
  table << md.rdbuf();
  EXPECT_THAT(table.str(), HasSubstr("all answers equal"));
  EXPECT_THAT(table.str(), HasSubstr("1 of 2 fitted"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mrh::psychophysics
