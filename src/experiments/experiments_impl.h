// SPDX-License-Identifier: Apache-2.0
// The experiment drivers behind mrh::experiments::Run.
#pragma once

#include <filesystem>
#include <string>

namespace mrh::experiments::internal {

/// T4.1: single-rate vs impulse method on the moving 60 kg cube. Returns 0 if its checks pass.
int RunT41(const std::filesystem::path& out, bool quiet);

}  // namespace mrh::experiments::internal
