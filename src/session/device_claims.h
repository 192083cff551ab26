// SPDX-License-Identifier: Apache-2.0
// Several pointers' devices must be distinct hardware: no two open the same Force Dimension
// device, OpenHaptics device or UDP port.
#pragma once

#include <vector>

#include "mrh/session/session.h"
#include "session/json_node.h"

namespace mrh::session::internal {

/// `devices[i]` was read from `elements[i]` (the `pointers` array). With two or more pointers of
/// one real device type, each must name its own device: forcedimension by `device.id`,
/// openhaptics by `device.name` (both required then, and distinct), udp by the port of
/// `device.bind` (distinct unless 0, which the OS picks).
/// @throws mrh::InvalidArgument naming the later element's key, e.g. `pointers[1].device.id`,
/// and the earlier pointer that claims the same device.
void CheckDistinctDevices(const std::vector<Node>& elements,
                          const std::vector<DeviceConfig>& devices);

}  // namespace mrh::session::internal
