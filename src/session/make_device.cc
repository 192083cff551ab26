// SPDX-License-Identifier: Apache-2.0
// Session → device, through the device registry. Apart from build.cc so it links without the
// world and the engine.
#include <fmt/format.h>

#include "mrh/core/error.h"
#include "mrh/session/devices.h"
#include "mrh/session/session.h"

namespace mrh::session {
namespace {

std::unique_ptr<device::Device> MakeConfiguredDevice(const Session& session,
                                                     const DeviceConfig& config,
                                                     const std::string& key) {
  const std::optional<DeviceDescriptor> type = FindDevice(config.type);
  if (!type) {
    std::string known;
    for (const DeviceDescriptor& d : DeviceDescriptors()) {
      known += fmt::format("{}\"{}\"", known.empty() ? "" : ", ", d.name);
    }
    throw InvalidArgument(fmt::format("{}: {}.type: unknown device type \"{}\"; expected one of {}",
                                      session.file.string(), key, config.type, known));
  }
  return type->factory(DeviceSource{session, config, key});
}

}  // namespace

std::unique_ptr<device::Device> MakeDevice(const Session& session) {
  return MakePointerDevice(session, 0);
}

std::unique_ptr<device::Device> MakePointerDevice(const Session& session, int i) {
  const bool several = !session.pointer_devices.empty();
  const DeviceConfig& config =
      several ? session.pointer_devices.at(static_cast<std::size_t>(i)) : session.device;
  const std::string key = several ? fmt::format("pointers[{}].device", i) : "device";
  try {
    return MakeConfiguredDevice(session, config, key);
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    // Errors already located in the session pass through; others get the session and device.
    if (message.rfind(session.file.string() + ":", 0) == 0) throw;
    throw InvalidArgument(
        fmt::format("{}: {} ({}): {}", session.file.string(), key, config.type, message));
  }
}

}  // namespace mrh::session
