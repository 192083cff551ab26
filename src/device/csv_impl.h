// SPDX-License-Identifier: Apache-2.0
// Reads timed poses from a CSV file with a header (keyframe files and recorded ticks.csv).
#pragma once

#include <array>
#include <filesystem>
#include <string_view>
#include <vector>

#include "mrh/device/simulated.h"

namespace mrh::device::internal {

/// The header names of the eight columns a pose row needs, in the order t, x, y, z, qw, qx, qy,
/// qz (e.g. {"t", "px", ...} for ticks.csv).
using PoseColumns = std::array<std::string_view, 8>;

/// Reads every data row as a keyframe: the named columns may appear in any order, other columns
/// are ignored, blank lines are skipped, quaternions are normalized. `kind` describes the file in
/// messages (e.g. "keyframe CSV").
/// @throws mrh::InvalidArgument "<file>:<line>: ..." on an unreadable file, a missing column, a
/// short row, a non-numeric or non-finite value, a zero-norm quaternion, a time that does not
/// increase, or a file without data rows. Not RT-safe.
std::vector<Keyframe> ReadPoseCsv(const std::filesystem::path& path, const PoseColumns& columns,
                                  std::string_view kind);

}  // namespace mrh::device::internal
