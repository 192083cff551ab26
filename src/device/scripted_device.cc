// SPDX-License-Identifier: Apache-2.0
// The scripted device (piecewise-linear keyframes) and the keyframe CSV loader.
#include <utility>

#include "device/csv_impl.h"
#include "device/track_impl.h"
#include "mrh/device/simulated.h"

namespace mrh::device {

std::unique_ptr<Device> MakeScriptedDevice(std::vector<Keyframe> keyframes,
                                           const Specifications& specs) {
  internal::ValidateKeyframes(keyframes, "scripted device: keyframe");
  return internal::MakeTrackDevice(std::move(keyframes), specs);
}

std::vector<Keyframe> LoadKeyframesCsv(const std::filesystem::path& path) {
  static constexpr internal::PoseColumns kColumns = {"t", "x", "y", "z", "qw", "qx", "qy", "qz"};
  return internal::ReadPoseCsv(path, kColumns, "keyframe CSV");
}

}  // namespace mrh::device
