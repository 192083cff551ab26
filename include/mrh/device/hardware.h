// SPDX-License-Identifier: Apache-2.0
// Real devices: Force Dimension (DHD) and OpenHaptics (HD) loaded at run time, and a UDP device.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "mrh/device/device.h"

namespace mrh::device {

/// Session: `device.type = "forcedimension"`. The DHD library is dlopen()ed at construction; no
/// Force Dimension SDK is needed to build.
struct ForceDimensionSettings {
  /// A path or a soname searched by the dynamic loader (LD_LIBRARY_PATH, ld.so.conf).
  std::string library = "libdhd.so";
  /// Which device: -1 the default one (dhdOpen); 0..127 the id-th device the DHD enumerates
  /// (dhdOpenID), so that several devices on one machine each get their own.
  int id = -1;
};

/// Session: `device.type = "openhaptics"`. The HD library is dlopen()ed at construction.
struct OpenHapticsSettings {
  std::string library = "libHD.so";  ///< path or soname
  /// The device's name in Touch Setup / the config file; "" = HD_DEFAULT_DEVICE.
  std::string name;
};

/// Session: `device.type = "udp"`. Any process streams poses to `bind` and receives wrenches
/// (packet layouts in docs/devices.md and udp_device.cc).
struct UdpSettings {
  std::string bind = "127.0.0.1:47800";  ///< "host:port" (IPv4 dotted quad or "localhost")
  double timeout = 0.05;  ///< s without a pose before the force fades out (the watchdog)
  double fade = 0.05;     ///< s, length of that fade
};

/// Loads `settings.library` and resolves the required DHD symbols (the optional ones are probed).
/// Open() opens the default device (dhdOpen) or, with `settings.id` >= 0, that device
/// (dhdOpenID), and enables forces; every later call names the device ID the open returned, so
/// several devices can run side by side. Close() zeroes the force, disables it and closes.
/// Read/SetWrench call the DHD on the calling (haptic) thread; a DHD error there is counted
/// (counters().vendor_errors, last_error()) and the last good reading is kept. Positions in m and
/// forces in N, device frame (x toward the user, z up). `specs.has_torque == false` (3-DOF devices)
/// drops and counts any torque.
/// @throws mrh::InvalidArgument naming the library path and dlerror() if it cannot be loaded
/// or lacks a required symbol (dhdOpenID when `settings.id` >= 0), or naming `device.id` if it
/// is outside -1..127; Open() throws mrh::RuntimeError with dhdErrorGetLastStr().
std::unique_ptr<Device> MakeForceDimensionDevice(const ForceDimensionSettings& settings,
                                                 const Specifications& specs);

/// Loads the HD library. Open() initializes the device, enables HD_FORCE_OUTPUT, schedules a
/// servo callback and starts the vendor's scheduler, which owns the 1 kHz servo thread. The
/// callback reads HD_CURRENT_TRANSFORM (column-major 4x4, mm → m) and writes HD_CURRENT_FORCE.
/// Two ways to drive it:
///  - as any Device: Read() returns the callback's newest reading and SetWrench() hands the
///    wrench to the next callback (lock-free triple buffers, the caller's thread at any rate);
///  - through ServoDevice::SetServoClient(): the callback itself calls the client (for example
///    Engine::Tick in embedded mode), so the engine runs on the vendor's thread.
/// HD errors inside the callback are counted; Open() errors throw mrh::RuntimeError.
/// Several devices (each by `settings.name`) share HD's one scheduler: each callback makes its
/// own device current, a device joins or leaves with the scheduler briefly stopped, and the
/// scheduler runs while any of them is open.
/// @throws mrh::InvalidArgument if the library or a symbol is missing (path and dlerror()).
std::unique_ptr<Device> MakeOpenHapticsDevice(const OpenHapticsSettings& settings,
                                              const Specifications& specs);

/// Status bits the UDP device adds to the safety layer's bits in each wrench packet.
enum UdpStatusBits : std::uint32_t {
  kUdpPoseTimeout = 1u << 16,    ///< no pose for `timeout`: the force is fading or faded out
  kUdpTorqueDropped = 1u << 17,  ///< a 3-DOF device (limits.output_dof 3) dropped the torque
};

/// The network device. bound_port() tells which port Open() bound (useful with port 0).
class UdpDevice : public Device {
 public:
  /// The local port after Open(), 0 before. Not RT-safe.
  virtual int bound_port() const = 0;
};

/// Binds a UDP socket (Open()) and starts a receiving thread that keeps the newest pose packet.
/// Read() takes the newest pose (never blocks); SetWrench() sends one wrench packet to the
/// address of the last pose. No pose for `timeout` fades the force to zero over `fade` and is
/// counted; malformed packets are counted and dropped.
/// @throws mrh::InvalidArgument for a bad `bind`; Open() throws mrh::RuntimeError if the socket
/// cannot be bound (the OS's reason included).
std::unique_ptr<UdpDevice> MakeUdpDevice(const UdpSettings& settings, const Specifications& specs);

/// Validates UdpSettings::bind. @throws mrh::InvalidArgument naming the value.
void CheckUdpBind(const std::string& bind);

/// Called by a device whose vendor library owns the servo thread, once per servo tick, with the
/// reading (device frame, t in s since the scheduler started); returns the wrench to display
/// (device frame). Must be RT-safe.
class ServoClient {
 public:
  virtual ~ServoClient() = default;
  virtual Wrench OnServoTick(double t, const DeviceState& reading) noexcept = 0;
};

/// A device whose vendor scheduler runs the servo loop (OpenHaptics).
class ServoDevice : public Device {
 public:
  /// Sets (or, with nullptr, clears) the client the servo callback calls. Set it before Open()
  /// or while the scheduler runs; the client must outlive Close(). Not RT-safe.
  virtual void SetServoClient(ServoClient* client) = 0;
};

}  // namespace mrh::device
