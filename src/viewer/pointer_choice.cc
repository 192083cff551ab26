// SPDX-License-Identifier: Apache-2.0
// PointerNames, ChoosePointer, PointerDevice.
#include "viewer/pointer_choice.h"

namespace mrh::viewer::internal {

std::vector<std::string> PointerNames(const session::Session& session) {
  const settings::EngineSettings& s = session.engine;
  if (s.pointers.empty()) return {s.pointer.body};
  std::vector<std::string> names;
  names.reserve(s.pointers.size());
  for (const settings::PointerLaneSettings& lane : s.pointers) names.push_back(lane.pointer.body);
  return names;
}

int ChoosePointer(int chosen, int count) noexcept {
  return chosen >= 0 && chosen < count ? chosen : 0;
}

const session::DeviceConfig& PointerDevice(const session::Session& session, int i) {
  if (session.pointer_devices.empty()) return session.device;
  return session.pointer_devices.at(static_cast<std::size_t>(i));
}

}  // namespace mrh::viewer::internal
