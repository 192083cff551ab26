// SPDX-License-Identifier: Apache-2.0
// CheckDistinctDevices: two pointers never drive one device.
#include "session/device_claims.h"

#include <fmt/format.h>

#include <string>

namespace mrh::session::internal {
namespace {

// The port of a "host:port" that device::CheckUdpBind accepted.
int UdpPort(const std::string& bind) {
  return std::stoi(bind.substr(bind.rfind(':') + 1));
}

std::size_t CountType(const std::vector<DeviceConfig>& devices, const std::string& type) {
  std::size_t n = 0;
  for (const DeviceConfig& d : devices) n += d.type == type ? 1 : 0;
  return n;
}

// The key of element `i`'s device that names its hardware, required once two pointers share a
// device type: without it both would open the vendor's default device.
Node NamingKey(const Node& element, const char* key, const char* expected) {
  return element.Require("device", "").Require(key, expected);
}

// Pointer element `element`'s device d against pointers[j]'s device e: two of a type must
// name distinct hardware (device index, device name, UDP port).
void CheckPairDistinct(const Node& element, const DeviceConfig& d, const DeviceConfig& e,
                       std::size_t j) {
  if (d.type != e.type) return;
  if (d.type == "forcedimension" && d.forcedimension.id == e.forcedimension.id) {
    NamingKey(element, "id", "")
        .Fail(fmt::format("{} is also pointers[{}].device.id", d.forcedimension.id, j),
              "a distinct device index per pointer");
  }
  if (d.type == "openhaptics" && d.openhaptics.name == e.openhaptics.name) {
    NamingKey(element, "name", "")
        .Fail(fmt::format("\"{}\" is also pointers[{}].device.name", d.openhaptics.name, j),
              "a distinct device name per pointer");
  }
  if (d.type == "udp" && UdpPort(d.udp.bind) != 0 && UdpPort(d.udp.bind) == UdpPort(e.udp.bind)) {
    const Node device = element.Require("device", "");
    const std::string what = fmt::format("port {} is also pointers[{}].device.bind's (\"{}\")",
                                         UdpPort(d.udp.bind), j, e.udp.bind);
    const std::string expected = "a distinct port per pointer, e.g. \"127.0.0.1:47801\"";
    if (const auto bind = device.Find("bind")) bind->Fail(what, expected);
    device.Fail(what + " (the default bind)", expected);
  }
}

}  // namespace

void CheckDistinctDevices(const std::vector<Node>& elements,
                          const std::vector<DeviceConfig>& devices) {
  const bool several_dhd = CountType(devices, "forcedimension") > 1;
  const bool several_hd = CountType(devices, "openhaptics") > 1;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const DeviceConfig& d = devices[i];
    if (d.type == "forcedimension" && several_dhd) {
      (void)NamingKey(elements[i], "id",
                      "each forcedimension pointer's device index (0, 1, ...): with several, "
                      "the default device would be opened twice");
    }
    if (d.type == "openhaptics" && several_hd) {
      const Node name = NamingKey(elements[i], "name",
                                  "each openhaptics pointer's device name from Touch Setup: "
                                  "with several, the default device would be opened twice");
      if (d.openhaptics.name.empty()) {
        name.Fail("an empty name (the default device)", "the device's name from Touch Setup");
      }
    }
    for (std::size_t j = 0; j < i; ++j) CheckPairDistinct(elements[i], d, devices[j], j);
  }
}

}  // namespace mrh::session::internal
