// SPDX-License-Identifier: Apache-2.0
// Shared helpers of the session tests: the fixture folder, minimal sessions, error matchers.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/session/session.h"

namespace mrh::session::testing {

/// tests/session/fixtures: scene.xml, approach.csv, ticks.csv and session files.
inline std::filesystem::path FixturesDir() {
  return std::filesystem::path(MRH_SOURCE_DIR) / "tests" / "session" / "fixtures";
}

/// Parses `text` as if it were fixtures/session.json.
inline Session Parse(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return ParseSession(text, FixturesDir(), overrides, "session.json");
}

/// A valid session (fixed device at the origin) with `extra` top-level members appended, e.g.
/// Minimal(R"("physics_dt": 0.01)").
inline std::string Minimal(const std::string& extra = "") {
  return R"({"scene": "scene.xml", "device": {"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0]})" +
         (extra.empty() ? std::string() : ", " + extra) + "}";
}

/// A session with the given `device` object (JSON text).
inline std::string WithDevice(const std::string& device) {
  return R"({"scene": "scene.xml", "device": )" + device + "}";
}

/// Matches a callable that throws mrh::InvalidArgument whose message contains `text`.
inline auto ThrowsInvalid(const std::string& text) {
  return ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr(text));
}

/// Matches a callable that throws mrh::InvalidArgument with exactly this message.
inline auto ThrowsInvalidExactly(const std::string& text) {
  return ::testing::ThrowsMessage<InvalidArgument>(::testing::StrEq(text));
}

}  // namespace mrh::session::testing
