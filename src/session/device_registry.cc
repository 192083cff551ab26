// SPDX-License-Identifier: Apache-2.0
// The registry of device types: names → factories, the built-in types registered on first use.
#include <fmt/format.h>

#include <map>
#include <mutex>

#include "mrh/core/error.h"
#include "mrh/device/external.h"
#include "mrh/device/hardware.h"
#include "mrh/device/simulated.h"
#include "mrh/session/devices.h"

namespace mrh::session {
namespace {

std::map<std::string, DeviceDescriptor>& Registry() {
  static std::map<std::string, DeviceDescriptor> registry;
  return registry;
}

std::mutex& RegistryMutex() {
  static std::mutex mutex;
  return mutex;
}

void Add(DeviceDescriptor descriptor) {
  const std::lock_guard lock(RegistryMutex());
  std::string name = descriptor.name;
  Registry()[std::move(name)] = std::move(descriptor);
}

// The scripted target: inline keyframes, or the CSV file the session names.
std::vector<device::Keyframe> TargetKeyframes(const DeviceSource& s) {
  if (s.config.trajectory.empty()) return s.config.keyframes;
  try {
    return device::LoadKeyframesCsv(s.config.trajectory);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(
        fmt::format("{}: {}.trajectory: {}", s.session.file.string(), s.key, e.what()));
  }
}

std::unique_ptr<device::Device> Fixed(const DeviceSource& s) {
  return device::MakeFixedDevice(s.config.pose, s.config.specs);
}

std::unique_ptr<device::Device> Scripted(const DeviceSource& s) {
  return device::MakeScriptedDevice(TargetKeyframes(s), s.config.specs);
}

std::unique_ptr<device::Device> Hand(const DeviceSource& s) {
  return device::MakeHandDevice(TargetKeyframes(s), s.config.hand, s.config.specs);
}

std::unique_ptr<device::Device> Replay(const DeviceSource& s) {
  return device::MakeReplayDevice(s.config.replay, s.config.specs);
}

std::unique_ptr<device::Device> External(const DeviceSource& s) {
  return std::make_unique<device::ExternalDevice>(s.config.specs);
}

std::unique_ptr<device::Device> ForceDimension(const DeviceSource& s) {
  return device::MakeForceDimensionDevice(s.config.forcedimension, s.config.specs);
}

std::unique_ptr<device::Device> OpenHaptics(const DeviceSource& s) {
  return device::MakeOpenHapticsDevice(s.config.openhaptics, s.config.specs);
}

std::unique_ptr<device::Device> Udp(const DeviceSource& s) {
  return device::MakeUdpDevice(s.config.udp, s.config.specs);
}

// Built-in types register on first use: self-registering statics would be dropped by the
// linker from a static library. One call per type; the parser reads each built-in type's own
// keys (session/schema.h, kDeviceTypes).
void RegisterBuiltins() {
  static std::once_flag once;
  std::call_once(once, [] {
    Add({"fixed", "holds the grip at device.pose", Fixed});
    Add({"scripted", "moves the grip through keyframes (inline or a CSV trajectory)", Scripted});
    Add({"hand", "a simulated hand following keyframes, pushed back by the force", Hand});
    Add({"replay", "replays the device poses of a recorded run's ticks.csv", Replay});
    Add({"external", "fed by the caller's servo loop (Engine::Start/Tick/Stop)", External});
    Add({"forcedimension", "a Force Dimension device through libdhd, loaded at run time",
         ForceDimension});
    Add({"openhaptics", "a 3D Systems device through OpenHaptics (libHD), loaded at run time",
         OpenHaptics});
    Add({"udp", "poses in, wrenches out over UDP", Udp});
  });
}

}  // namespace

// The built-ins first, so that a program's type of the same name replaces the built-in one.
void RegisterDevice(DeviceDescriptor descriptor) {
  RegisterBuiltins();
  Add(std::move(descriptor));
}

std::optional<DeviceDescriptor> FindDevice(const std::string& name) {
  RegisterBuiltins();
  const std::lock_guard lock(RegistryMutex());
  const auto it = Registry().find(name);
  if (it == Registry().end()) return std::nullopt;
  return it->second;
}

std::vector<DeviceDescriptor> DeviceDescriptors() {
  RegisterBuiltins();
  const std::lock_guard lock(RegistryMutex());
  std::vector<DeviceDescriptor> out;
  for (const auto& [name, descriptor] : Registry()) out.push_back(descriptor);
  return out;
}

}  // namespace mrh::session
