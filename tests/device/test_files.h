// SPDX-License-Identifier: Apache-2.0
// Writes small text files for the CSV loader tests, one per test so parallel runs do not collide.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace mrh::device::testing {

/// Writes `text` to a file named after the running test (and the process id) in the test temp
/// directory and returns its path.
inline std::filesystem::path WriteTestFile(const std::string& suffix, const std::string& text) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path path =
      std::filesystem::path(::testing::TempDir()) /
      (std::string("mrh_") + info->test_suite_name() + "_" + info->name() + "_" +
       std::to_string(::getpid()) + "_" + suffix);
  std::ofstream out(path);
  out << text;
  return path;
}

}  // namespace mrh::device::testing
