// SPDX-License-Identifier: Apache-2.0
// The replay device: the tool poses of a recorded ticks.csv, interpolated by time.
#include "device/csv_impl.h"
#include "device/track_impl.h"
#include "mrh/device/simulated.h"

namespace mrh::device {

std::unique_ptr<Device> MakeReplayDevice(const std::filesystem::path& ticks_csv,
                                         const Specifications& specs) {
  static constexpr internal::PoseColumns kColumns = {"t", "px", "py", "pz", "qw", "qx", "qy", "qz"};
  // ReadPoseCsv already checks what ValidateKeyframes would (finite, unit, increasing).
  return internal::MakeTrackDevice(internal::ReadPoseCsv(ticks_csv, kColumns, "ticks.csv"), specs);
}

}  // namespace mrh::device
