// SPDX-License-Identifier: Apache-2.0
// Shared helpers of the experiment drivers: locating scenes, machine tags, result files.
#pragma once

#include <filesystem>
#include <string>

namespace mrh::experiments::internal {

/// The folder holding the shared scenes: $MRH_SCENES_DIR, else the source tree's scenes/, else
/// the installed share/mrhaptics/scenes. @throws mrh::RuntimeError if none exists.
std::filesystem::path ScenesDir();

/// One line naming the machine (CPU model, cores, kernel) for tagging results.
std::string MachineTag();

/// Writes `text` to `path`. @throws mrh::RuntimeError naming the path on failure.
void WriteText(const std::filesystem::path& path, const std::string& text);

}  // namespace mrh::experiments::internal
