// SPDX-License-Identifier: Apache-2.0
// The registry of device types: the session key device.type → the factory of that device.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mrh/device/device.h"
#include "mrh/session/session.h"

namespace mrh::session {

/// What a device factory builds from: the parsed session, the device block of the pointer being
/// built, and that block's key ("device" or "pointers[1].device") for messages.
struct DeviceSource {
  const Session& session;
  const DeviceConfig& config;
  std::string key;
};

/// Builds one device (setup thread). Its specifications should be config.specs, which hold the
/// block's `model` and `limits`; the engine applies config.calibration. @throws
/// mrh::InvalidArgument naming the key at fault (MakeDevice prefixes the file and the key).
using DeviceFactory = std::function<std::unique_ptr<device::Device>(const DeviceSource&)>;

/// Everything the session parser and MakeDevice know of a device type.
struct DeviceDescriptor {
  std::string name;     ///< session key device.type, e.g. "scripted"
  std::string summary;  ///< one line for listings
  DeviceFactory factory;
};

/// Registers a device type; a later registration under the same name replaces the earlier one.
/// Register before LoadSession: the parser accepts the registered names as device.type. A type
/// registered here takes the keys every device block has (type, model, limits, calibration);
/// the built-in types' own keys (pose, keyframes, ...) are read by the parser.
/// Thread-safe (setup path: allocates).
void RegisterDevice(DeviceDescriptor descriptor);

/// The descriptor of device type `name`, or nullopt if none is registered under it.
std::optional<DeviceDescriptor> FindDevice(const std::string& name);

/// Every registered device type, sorted by name.
std::vector<DeviceDescriptor> DeviceDescriptors();

}  // namespace mrh::session
