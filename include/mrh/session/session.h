// SPDX-License-Identifier: Apache-2.0
// Session files (JSON): which scene, method, rates, pointer, gains and device a run uses.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/device/calibration.h"
#include "mrh/device/device.h"
#include "mrh/device/hardware.h"
#include "mrh/device/simulated.h"
#include "mrh/settings/settings.h"

namespace mrh::world {
class World;
}

namespace mrh::engine {
class Engine;
}

namespace mrh::session {

/// The `device` block.
struct DeviceConfig {
  std::string type = "fixed";  ///< fixed | scripted | hand | replay | external | forcedimension
                               ///< | openhaptics | udp
  std::string model;           ///< device.model ("" = none): defaults for the limits
  Pose pose;                   ///< fixed: the held pose
  std::vector<device::Keyframe> keyframes;        ///< scripted / hand: inline keyframes
  std::filesystem::path trajectory;               ///< scripted / hand: CSV of keyframes (resolved)
  std::filesystem::path replay;                   ///< replay: a ticks.csv (resolved)
  device::HandSettings hand;                      ///< hand: the simulated user's parameters
  device::Specifications specs;                   ///< max_force, max_torque, ... overrides
  device::Calibration calibration;                ///< device → world
  device::ForceDimensionSettings forcedimension;  ///< forcedimension: device.library, device.id
  device::OpenHapticsSettings openhaptics;        ///< openhaptics: device.library, device.name
  device::UdpSettings udp;                        ///< udp: device.bind, timeout, fade
  /// True if device.model or device.limits.max_stiffness states the stiffness limit; then
  /// rendering.stiffness above specs.max_stiffness is a validation error.
  bool stiffness_limit_stated = false;
};

/// A parsed and validated session.
/// The method of a session that names none: the thesis' proposed 3-DOF method (local-dynamics,
/// contact local model), which needs only a sphere pointer, as every 3-DOF method.
inline constexpr const char* kDefaultSessionMethod = "local-dynamics";

struct Session {
  std::filesystem::path file;   ///< the session file ("<string>" if parsed from text)
  std::filesystem::path scene;  ///< MJCF path, resolved against the session's folder
  std::string keyframe;         ///< MJCF keyframe applied at start (may be empty)
  std::optional<Vec3> gravity;  ///< m/s², overrides the scene's
  settings::EngineSettings engine;
  DeviceConfig device;
  /// Several pointers (session key `pointers`): each pointer's device, in the order
  /// of engine.pointers; pointer_devices[0] equals `device`. Empty with one pointer.
  std::vector<DeviceConfig> pointer_devices;
};

/// Reads, overrides and validates a session file. `overrides` are "dotted.key=value" strings
/// (value parsed as JSON, else taken as a string), applied before validation.
/// @throws mrh::InvalidArgument with a one-line message naming the file, the key and the fix
/// (unknown keys, wrong types, bad values, unreadable file).
Session LoadSession(const std::filesystem::path& file,
                    const std::vector<std::string>& overrides = {});

/// Same, from JSON text; relative paths resolve against `base_dir`.
Session ParseSession(const std::string& json_text, const std::filesystem::path& base_dir,
                     const std::vector<std::string>& overrides = {},
                     const std::string& origin = "<string>");

/// Loads the scene (with the session's pointer body) and applies the keyframe and gravity. The
/// timestep is left to the engine, which sets physics_dt (haptic_dt for single-rate methods).
/// @throws mrh::SceneError.
world::World LoadWorld(const Session& session);

/// Builds the configured device. @throws mrh::InvalidArgument (e.g. unreadable trajectory).
std::unique_ptr<device::Device> MakeDevice(const Session& session);
/// Builds pointer i's device (`device` when the session has one pointer).
/// @throws mrh::InvalidArgument naming `pointers[i].device`.
std::unique_ptr<device::Device> MakePointerDevice(const Session& session, int i);

/// LoadWorld + MakeDevice + engine construction. Every error starts with the file to edit (the
/// session's, unless it names the scene or a data file).
std::unique_ptr<engine::Engine> MakeEngine(const Session& session);
/// The same with a device the caller built (e.g. to read its counters after the run).
std::unique_ptr<engine::Engine> MakeEngine(const Session& session,
                                           std::unique_ptr<device::Device> device);

}  // namespace mrh::session
