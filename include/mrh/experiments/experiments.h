// SPDX-License-Identifier: Apache-2.0
// Reproducible experiments (the thesis' evaluations), run by name from `mrh experiment`.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace mrh::experiments {

/// Runs the experiment `name`, writing its CSV, summary and plots under `out` (created if
/// needed). `quiet` suppresses progress output on stdout/stderr. Returns the process exit code
/// (0 when every check of the experiment passed).
/// @throws mrh::InvalidArgument for an unknown name (listing the known ones);
/// mrh::RuntimeError on I/O failure. Not RT-safe.
int Run(const std::string& name, const std::filesystem::path& out, bool quiet);

/// As Run; `full` runs the experiment's big sweep where it has one (e.g. t4.3: 1000 cubes, 500
/// with friction), otherwise the default run.
int Run(const std::string& name, const std::filesystem::path& out, bool quiet, bool full);

/// Registered experiments as (name, one-line summary), sorted by name.
std::vector<std::pair<std::string, std::string>> List();

}  // namespace mrh::experiments
