// SPDX-License-Identifier: Apache-2.0
// The `device` block: type-specific keys, poses, keyframes, paths, limits and calibration.
#include "session/device_config.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"
#include "mrh/device/models.h"
#include "mrh/session/devices.h"

namespace mrh::session::internal {
namespace {

// Upper bounds of device.limits (docs/session-format.md, "Ranges"), in kLimitFields order.
constexpr std::array<double, 3> kMaxLimits{1e4, 1e3, 1e7};

constexpr std::string_view kPoseLayout = "[x, y, z, qw, qx, qy, qz] (m, quaternion)";
constexpr std::string_view kKeyframeLayout = "[t, x, y, z, qw, qx, qy, qz] (s, m, quaternion)";

std::vector<std::string_view> AllDeviceKeys() {
  std::vector<std::string_view> keys(kDeviceCommonKeys.begin(), kDeviceCommonKeys.end());
  for (const DeviceType& type : kDeviceTypes) {
    for (const std::string_view key : type.keys) {
      if (!key.empty() && std::find(keys.begin(), keys.end(), key) == keys.end()) {
        keys.push_back(key);
      }
    }
  }
  return keys;
}

bool IsBuiltinType(std::string_view name) {
  return std::any_of(kDeviceTypes.begin(), kDeviceTypes.end(), [&](const DeviceType& type) {
    return type.name == name;
  });
}

// "fixed", "scripted", ... for messages: the built-in types, then those registered by the
// program (mrh/session/devices.h).
std::string TypeNames() {
  std::vector<std::string> names;
  for (const DeviceType& type : kDeviceTypes) names.push_back(fmt::format("\"{}\"", type.name));
  for (const DeviceDescriptor& d : DeviceDescriptors()) {
    if (!IsBuiltinType(d.name)) names.push_back(fmt::format("\"{}\"", d.name));
  }
  return fmt::format("{}", fmt::join(names, ", "));
}

// The type `name` and the keys only it accepts: a built-in type's from kDeviceTypes, none for a
// registered one. `name` must outlive the result.
DeviceType ParseType(const Node& node, const std::string& name) {
  for (const DeviceType& type : kDeviceTypes) {
    if (type.name == name) return type;
  }
  if (FindDevice(name)) return DeviceType{name, {}};
  node.Fail(fmt::format("unknown device type \"{}\"", name), "one of " + TypeNames());
}

// Keys of other device types are errors, so a leftover `pose` on a scripted device is not
// silently ignored.
void RejectForeignKeys(const Node& device, const DeviceType& type) {
  std::vector<std::string_view> own(kDeviceCommonKeys.begin(), kDeviceCommonKeys.end());
  for (const std::string_view key : type.keys) {
    if (!key.empty()) own.push_back(key);
  }
  for (const auto& [key, unused] : device.value().items()) {
    if (std::find(own.begin(), own.end(), key) != own.end()) continue;
    device.Find(key)->Fail(
        fmt::format("not used by device type \"{}\"", type.name),
        fmt::format("only the keys of a {} device: {}", type.name, fmt::join(own, ", ")));
  }
}

// Device poses follow the rules of every device data source (mrh/core/validate.h).
Pose CheckedPose(const Node& node, const double* v) {
  const Vec3 p(v[0], v[1], v[2]);
  const Problem problem = PoseProblem(p, Quat(v[3], v[4], v[5], v[6]));
  if (problem) node.Fail(problem.what, problem.expected);
  return Pose{p, ParseQuaternion(node, v[3], v[4], v[5], v[6])};
}

Pose ParsePose(const Node& node) {
  const std::vector<double> v = node.Numbers(7, kPoseLayout);
  return CheckedPose(node, v.data());
}

std::vector<device::Keyframe> ParseKeyframes(const Node& node) {
  const std::vector<Node> elements =
      node.Elements("an array of keyframes " + std::string(kKeyframeLayout));
  if (elements.empty()) node.Fail("found an empty array", "at least one keyframe");
  std::vector<device::Keyframe> keyframes;
  for (const Node& element : elements) {
    const std::vector<double> v = element.Numbers(8, kKeyframeLayout);
    const Problem problem = KeyframeTimeProblem(v[0], keyframes.empty() ? NAN : keyframes.back().t);
    if (problem) element.Fail(problem.what, problem.expected);
    keyframes.push_back(device::Keyframe{v[0], CheckedPose(element, v.data() + 1)});
  }
  return keyframes;
}

// Scripted and hand devices follow keyframes given inline or in a CSV file, never both.
void ParseTarget(const Node& device, std::string_view type, DeviceConfig* config) {
  const std::optional<Node> keyframes = device.Find("keyframes");
  const std::optional<Node> trajectory = device.Find("trajectory");
  const std::string expected =
      fmt::format(R"(exactly one of "keyframes" and "trajectory" for a {} device)", type);
  if (keyframes && trajectory)
    device.Fail(R"(both "keyframes" and "trajectory" are set)", expected);
  if (!keyframes && !trajectory) {
    device.Fail(R"(neither "keyframes" nor "trajectory" is set)", expected);
  }
  if (keyframes) config->keyframes = ParseKeyframes(*keyframes);
  if (trajectory) config->trajectory = trajectory->ExistingFile("a keyframe CSV file");
}

// The model's data sheet first, then the explicit limits over it.
void ParseModel(const Node& device, DeviceConfig* config) {
  const std::optional<Node> node = device.Find("model");
  if (!node) return;
  const std::string name = node->String();
  const device::DeviceModel* model = device::FindDeviceModel(name);
  if (model == nullptr) {
    node->Fail(fmt::format("unknown device model \"{}\"", name),
               "one of " + device::DeviceModelNames());
  }
  config->model = name;
  config->specs = device::ModelSpecifications(*model);
  config->stiffness_limit_stated = true;
}

void ParseLimitSpecials(const Node& limits, device::Specifications* specs) {
  if (const auto radius = limits.Find("workspace_radius")) {
    const double r = radius->Number("m");
    if (!(r > 0.0)) radius->Fail(fmt::format("{} m", r), "a number > 0");
    specs->workspace_min = Vec3::Constant(-r);
    specs->workspace_max = Vec3::Constant(r);
  }
  if (const auto dof = limits.Find("output_dof")) {
    const int n = dof->Integer();
    if (n != 3 && n != 6) dof->Fail(fmt::format("{}", n), "3 (force only) or 6 (force and torque)");
    specs->has_torque = n == 6;
  }
}

void ParseLimits(const Node& device, DeviceConfig* config) {
  const std::optional<Node> limits = device.Find("limits");
  if (!limits) return;
  std::vector<std::string_view> keys = KeysOf(kLimitFields);
  keys.insert(keys.end(), kLimitSpecialKeys.begin(), kLimitSpecialKeys.end());
  limits->ExpectObject(keys, "an object");
  device::Specifications* specs = &config->specs;
  ReadFields(*limits, kLimitFields, specs);
  for (std::size_t i = 0; i < kLimitFields.size(); ++i) {
    const auto& field = kLimitFields[i];
    const std::optional<Node> node = limits->Find(field.key);
    const double value = specs->*std::get<double device::Specifications::*>(field.member);
    if (node && !(value > 0.0 && value <= kMaxLimits[i])) {
      node->Fail(fmt::format("{} {}", FormatNumber(value), field.unit),
                 fmt::format("a number > 0 and <= {} {}", FormatNumber(kMaxLimits[i]), field.unit));
    }
  }
  ParseLimitSpecials(*limits, specs);
  if (limits->Find("max_stiffness")) config->stiffness_limit_stated = true;
}

// A soname ("libdhd.so") is left to the dynamic loader's search; a path (with a '/') resolves
// against the session's folder and must exist.
std::string ParseLibrary(const Node& device, const std::string& fallback) {
  const std::optional<Node> node = device.Find("library");
  if (!node) return fallback;
  const std::string text = node->String();
  if (text.empty()) node->Fail("found an empty string", "a library path or soname");
  if (text.find('/') == std::string::npos) return text;
  return node->ExistingFile("the vendor's shared library").string();
}

void ParseUdp(const Node& device, device::UdpSettings* udp) {
  if (const auto bind = device.Find("bind")) {
    udp->bind = bind->String();
    try {
      device::CheckUdpBind(udp->bind);
    } catch (const InvalidArgument&) {
      bind->Fail(fmt::format("\"{}\" is not host:port", udp->bind),
                 "\"host:port\" with an IPv4 host and a port 0..65535, e.g. \"127.0.0.1:47800\"");
    }
  }
  if (const auto timeout = device.Find("timeout")) {
    udp->timeout = timeout->Number("s");
    if (!(udp->timeout > 0.0)) timeout->Fail(fmt::format("{} s", udp->timeout), "a number > 0");
  }
  if (const auto fade = device.Find("fade")) {
    udp->fade = fade->Number("s");
    if (!(udp->fade >= 0.0)) fade->Fail(fmt::format("{} s", udp->fade), "a number >= 0");
  }
}

// The keys of the hardware and network types.
void ParseHardware(const Node& device, const DeviceType& type, DeviceConfig* config) {
  if (type.name == "forcedimension") {
    config->forcedimension.library = ParseLibrary(device, config->forcedimension.library);
    if (const auto id = device.Find("id")) {
      config->forcedimension.id = id->Integer();
      if (config->forcedimension.id < 0 || config->forcedimension.id > 127) {
        id->Fail(std::to_string(config->forcedimension.id),
                 "the device's index among the connected Force Dimension devices, 0..127");
      }
    }
  } else if (type.name == "openhaptics") {
    config->openhaptics.library = ParseLibrary(device, config->openhaptics.library);
    if (const auto name = device.Find("name")) config->openhaptics.name = name->String();
  } else if (type.name == "udp") {
    ParseUdp(device, &config->udp);
  }
}

device::Calibration ParseCalibration(const Node& node) {
  node.ExpectObject({kCalibrationKeys.begin(), kCalibrationKeys.end()}, "an object");
  device::Calibration calibration;
  if (const auto position = node.Find("position")) {
    const std::vector<double> p = position->Numbers(3, "[x, y, z] (m)");
    calibration.X_WD.p = Vec3(p[0], p[1], p[2]);
    const Problem problem = PoseProblem(calibration.X_WD.p, Quat::Identity());
    if (problem) position->Fail(problem.what, problem.expected);
  }
  if (const auto orientation = node.Find("orientation")) {
    const std::vector<double> q = orientation->Numbers(4, "[qw, qx, qy, qz]");
    calibration.X_WD.q = ParseQuaternion(*orientation, q[0], q[1], q[2], q[3]);
  }
  if (const auto scale = node.Find("scale")) {
    calibration.scale = scale->Number("");
    if (!(calibration.scale >= 1e-3 && calibration.scale <= 1e3)) {
      scale->Fail(FormatNumber(calibration.scale),
                  "a number in [0.001, 1000] (world m per device m)");
    }
  }
  return calibration;
}

}  // namespace

Quat ParseQuaternion(const Node& node, double qw, double qx, double qy, double qz) {
  Quat q(qw, qx, qy, qz);
  const Problem problem = PoseProblem(Vec3::Zero(), q);
  if (problem) node.Fail(problem.what, problem.expected);
  q.normalize();
  return q;
}

DeviceConfig ParseDevice(const Node& device) {
  device.ExpectObject(AllDeviceKeys(), "an object");
  DeviceConfig config;
  const Node type_node = device.Require("type", "one of " + TypeNames());
  const std::string type_name = type_node.String();
  const DeviceType type = ParseType(type_node, type_name);
  config.type = type_name;
  RejectForeignKeys(device, type);
  if (type.name == "fixed") {
    config.pose =
        ParsePose(device.Require("pose", std::string(kPoseLayout) + " for a fixed device"));
  } else if (type.name == "scripted" || type.name == "hand") {
    ParseTarget(device, type.name, &config);
    ReadBlock(device, "hand", kHandFields, &config.hand);
  } else if (type.name == "replay") {
    config.replay = device.Require("replay", "the path of a recorded run's ticks.csv")
                        .ExistingFile("a recorded run's ticks.csv");
  }
  ParseHardware(device, type, &config);
  ParseModel(device, &config);
  ParseLimits(device, &config);
  if (const auto calibration = device.Find("calibration")) {
    config.calibration = ParseCalibration(*calibration);
  }
  return config;
}

void CheckStiffnessLimit(const Node& root, const DeviceConfig& device, double stiffness) {
  if (!device.stiffness_limit_stated || stiffness <= device.specs.max_stiffness) return;
  const std::string source =
      device.model.empty() ? std::string() : fmt::format(" (device.model \"{}\")", device.model);
  const std::string what =
      fmt::format("rendering.stiffness = {} N/m exceeds device.limits.max_stiffness = {} N/m{}",
                  stiffness, device.specs.max_stiffness, source);
  const std::string fix =
      "rendering.stiffness <= device.limits.max_stiffness, or raise device.limits.max_stiffness "
      "if the device renders it stably";
  const std::optional<Node> rendering = root.Find("rendering");
  const std::optional<Node> node = rendering ? rendering->Find("stiffness") : std::nullopt;
  if (node) node->Fail(what, fix);
  root.Require("device", "").Fail(what, fix);
}

}  // namespace mrh::session::internal
