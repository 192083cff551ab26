// SPDX-License-Identifier: Apache-2.0
// Session → simulated device. Apart from build.cc so it links without the world and the engine.
#include <fmt/format.h>

#include "mrh/core/error.h"
#include "mrh/device/external.h"
#include "mrh/device/hardware.h"
#include "mrh/session/session.h"

namespace mrh::session {
namespace {

// The scripted target: inline keyframes, or the CSV file the session names.
std::vector<device::Keyframe> TargetKeyframes(const Session& session, const DeviceConfig& config,
                                              const std::string& key) {
  if (config.trajectory.empty()) return config.keyframes;
  try {
    return device::LoadKeyframesCsv(config.trajectory);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(
        fmt::format("{}: {}.trajectory: {}", session.file.string(), key, e.what()));
  }
}

std::unique_ptr<device::Device> MakeConfiguredDevice(const Session& session,
                                                     const DeviceConfig& config,
                                                     const std::string& key) {
  if (config.type == "fixed") return device::MakeFixedDevice(config.pose, config.specs);
  if (config.type == "scripted") {
    return device::MakeScriptedDevice(TargetKeyframes(session, config, key), config.specs);
  }
  if (config.type == "hand") {
    return device::MakeHandDevice(TargetKeyframes(session, config, key), config.hand, config.specs);
  }
  if (config.type == "replay") return device::MakeReplayDevice(config.replay, config.specs);
  if (config.type == "external") return std::make_unique<device::ExternalDevice>(config.specs);
  if (config.type == "forcedimension") {
    return device::MakeForceDimensionDevice(config.forcedimension, config.specs);
  }
  if (config.type == "openhaptics") {
    return device::MakeOpenHapticsDevice(config.openhaptics, config.specs);
  }
  if (config.type == "udp") return device::MakeUdpDevice(config.udp, config.specs);
  throw InvalidArgument(
      fmt::format("{}: {}.type: unknown device type \"{}\"; expected \"fixed\", "
                  "\"scripted\", \"hand\", \"replay\", \"external\", \"forcedimension\", "
                  "\"openhaptics\" or \"udp\"",
                  session.file.string(), key, config.type));
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
