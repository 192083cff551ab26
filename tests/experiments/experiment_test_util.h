// SPDX-License-Identifier: Apache-2.0
// Shared by the experiment tests: per-process output folders and one experiment run per suite.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace mrh::experiments::testing {

/// `stem` followed by this process's id, under the system temp folder. Each test runs in its
/// own process (ctest, maybe in parallel), so each process writes to its own folder.
inline std::filesystem::path TempDir(const std::string& stem) {
  return std::filesystem::temp_directory_path() / (stem + std::to_string(getpid()));
}

/// The summary.json an experiment wrote into `out`.
/// @throws nlohmann::json::parse_error if it is missing or not JSON.
inline nlohmann::json ReadSummary(const std::filesystem::path& out) {
  std::ifstream in(out / "summary.json");
  return nlohmann::json::parse(in);
}

/// Expects summary["checks"] to be a non-empty object whose every value is true: a summary
/// without checks, or with none, fails (a loop over zero checks would pass silently).
inline void ExpectAllChecksPass(const nlohmann::json& summary) {
  ASSERT_TRUE(summary.contains("checks")) << "summary.json has no \"checks\"";
  const nlohmann::json& checks = summary["checks"];
  ASSERT_TRUE(checks.is_object()) << checks.dump();
  EXPECT_FALSE(checks.empty()) << "summary.json \"checks\" is empty";
  for (const auto& [name, pass] : checks.items()) {
    EXPECT_TRUE(pass.is_boolean() && pass.get<bool>()) << name << " = " << pass.dump();
  }
}

/// Fixture for a suite whose tests all check one run of an experiment. The suite's
/// SetUpTestSuite calls RunExperiment once; TearDownTestSuite removes the output folder.
/// `Suite` is the deriving fixture itself, so that every suite has its own run.
template <typename Suite>
class ExperimentTest : public ::testing::Test {
 protected:
  /// Runs `run(out)`, which returns the experiment's exit code, into the fresh folder
  /// TempDir(stem) and reads the summary.json it wrote.
  template <typename Run>
  static void RunExperiment(const std::string& stem, Run run) {
    out_ = new std::filesystem::path(TempDir(stem));
    std::filesystem::remove_all(*out_);
    exit_code_ = run(*out_);
    summary_ = new nlohmann::json(ReadSummary(*out_));
  }

  static void TearDownTestSuite() {
    if (out_ != nullptr) std::filesystem::remove_all(*out_);
    delete summary_;
    delete out_;
    summary_ = nullptr;
    out_ = nullptr;
  }

  // Pointers, created and deleted with the suite: no static object with a destructor.
  inline static std::filesystem::path* out_ = nullptr;
  inline static nlohmann::json* summary_ = nullptr;
  inline static int exit_code_ = -1;
};

}  // namespace mrh::experiments::testing
