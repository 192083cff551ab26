// SPDX-License-Identifier: Apache-2.0
// Session files: JSON text + `--set` overrides → a validated Session (no world or engine needed).
#include "mrh/session/session.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <system_error>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"
#include "mrh/engine/method.h"
#include "session/device_claims.h"
#include "session/device_config.h"
#include "session/json_node.h"
#include "session/json_text.h"
#include "session/overrides.h"
#include "session/schema.h"

namespace mrh::session {
namespace {

namespace fs = std::filesystem;
using internal::Context;
using internal::Node;

std::vector<std::string_view> TopLevelKeys() {
  std::vector<std::string_view> keys(internal::kTopLevelSpecialKeys.begin(),
                                     internal::kTopLevelSpecialKeys.end());
  for (const auto& field : internal::kEngineFields) keys.push_back(field.key);
  keys.insert(keys.end(), internal::kTopLevelBlocks.begin(), internal::kTopLevelBlocks.end());
  return keys;
}

// Documented bound of the session's and the scene's gravity (docs/session-format.md, "Ranges").
constexpr double kMaxGravity = 1e3;

// The method must be registered; the message lists them and the closest one.
void CheckMethod(const Node& node) {
  const std::string name = node.String();
  std::vector<std::string> names;
  for (const auto& [method, summary] : engine::ListMethods()) names.push_back(method);
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  const std::vector<std::string_view> views(names.begin(), names.end());
  const auto closest = internal::ClosestName(name, views);
  node.Fail(fmt::format("unknown method \"{}\"", name),
            fmt::format("one of: {}{} (see `mrh methods`)", fmt::join(names, ", "),
                        closest ? fmt::format(" (did you mean \"{}\"?)", *closest) : ""));
}

settings::Mode ParseMode(const Node& node) {
  const std::string mode = node.String();
  if (mode == "lockstep") return settings::Mode::kLockstep;
  if (mode == "realtime") return settings::Mode::kRealtime;
  node.Fail(fmt::format("unknown mode \"{}\"", mode), R"("lockstep" or "realtime")");
}

// The rendering block: its plain fields plus `rotation_weight` ([Rxx, Ryy, Rzz] in m^2).
void ReadRendering(const Node& root, settings::RenderingSettings* out) {
  const std::optional<Node> block = root.Find("rendering");
  if (!block) return;
  std::vector<std::string_view> keys = internal::KeysOf(internal::kRenderingFields);
  keys.insert(keys.end(), internal::kRenderingSpecialKeys.begin(),
              internal::kRenderingSpecialKeys.end());
  block->ExpectObject(keys, "an object");
  internal::ReadFields(*block, internal::kRenderingFields, out);
  if (const auto weight = block->Find("rotation_weight")) {
    const std::vector<double> w = weight->Numbers(3, "[Rxx, Ryy, Rzz] (m^2)");
    out->rotation_weight = Vec3(w[0], w[1], w[2]);
  }
  if (const auto inertia = block->Find("tool_inertia")) {
    const std::vector<double> w = inertia->Numbers(3, "[Ixx, Iyy, Izz] (kg*m^2)");
    out->tool_inertia = Vec3(w[0], w[1], w[2]);
  }
}

// `materials`: an object of named materials, each a block of optional gains and an optional
// `vibration` whose three keys are all required (a transient has no rendering.* default).
void ReadMaterials(const Node& root, settings::RenderingSettings* out) {
  const std::optional<Node> block = root.Find("materials");
  if (!block) return;
  if (!block->value().is_object()) {
    block->Fail(internal::Describe(block->value()), "an object of named materials");
  }
  std::vector<std::string_view> keys = internal::KeysOf(internal::kMaterialFields);
  keys.push_back("vibration");
  for (const auto& [name, value] : block->value().items()) {
    const Node material = block->Require(name, "a material");
    material.ExpectObject(keys, "an object");
    settings::MaterialSettings settings;
    internal::ReadFields(material, internal::kMaterialFields, &settings);
    if (const auto vibration = material.Find("vibration")) {
      vibration->ExpectObject(internal::KeysOf(internal::kVibrationFields), "an object");
      settings::VibrationSettings v;
      for (const auto& field : internal::kVibrationFields) {
        v.*std::get<double settings::VibrationSettings::*>(field.member) =
            vibration->Require(field.key, "a number").Number(field.unit);
      }
      settings.vibration = v;
    }
    out->materials[name] = settings;
  }
}

// A real device answers in wall-clock time, and lockstep runs the simulation as fast as it can
// without waiting for it (8 s of simulation in 0.02 s, no packet answered): such a session runs
// in real time unless it says otherwise, and saying "lockstep" is an error.
void RequireRealtimeForRealDevice(const Node& root, const std::string& type,
                                  settings::EngineSettings* engine) {
  if (type != "forcedimension" && type != "openhaptics" && type != "udp") return;
  const auto mode = root.Find("mode");
  if (!mode) {
    engine->mode = settings::Mode::kRealtime;
  } else if (engine->mode != settings::Mode::kRealtime) {
    mode->Fail(
        fmt::format("\"{}\" with the real device \"{}\"", settings::ModeName(engine->mode), type),
        "\"realtime\" (lockstep never waits for the device; drop the key, set "
        "\"mode\": \"realtime\" or run with --mode realtime)");
  }
}

// One element of `pointers`: body (required), radius, device (required) and rendering overrides
// on top of the session's `rendering`.
settings::PointerLaneSettings ReadPointerElement(const Node& element,
                                                 const settings::RenderingSettings& base,
                                                 DeviceConfig* device) {
  element.ExpectObject({"body", "radius", "device", "rendering"},
                       "an object with \"body\", \"device\" and optional \"radius\" and "
                       "\"rendering\"");
  settings::PointerLaneSettings lane;
  lane.pointer.body = element.Require("body", "the pointer's mocap body (string)").String();
  if (const auto radius = element.Find("radius")) lane.pointer.radius = radius->Number("m");
  lane.rendering = base;
  ReadRendering(element, &lane.rendering);
  *device = internal::ParseDevice(
      element.Require("device", "an object with at least \"type\" (see docs/session-format.md)"));
  if (device->stiffness_limit_stated && lane.rendering.stiffness > device->specs.max_stiffness) {
    element.Fail(fmt::format("rendering.stiffness = {} N/m exceeds device.limits.max_stiffness = "
                             "{} N/m",
                             lane.rendering.stiffness, device->specs.max_stiffness),
                 "rendering.stiffness <= device.limits.max_stiffness for this pointer");
  }
  return lane;
}

// `pointers`: a list of pointers, each with its own device; one element is the
// single `pointer` + `device` form. The two forms do not mix.
void ReadPointers(const Node& root, const Node& pointers, Session* session) {
  for (const char* key : {"pointer", "device"}) {
    if (root.Find(key)) {
      pointers.Fail(fmt::format("given together with \"{}\"", key),
                    "either \"pointers\": [...] (each element with its own body and device) or "
                    "\"pointer\" + \"device\", not both");
    }
  }
  const std::vector<Node> elements =
      pointers.Elements("an array of pointers [{\"body\": ..., \"device\": {...}}, ...]");
  if (elements.empty()) pointers.Fail("an empty array", "at least one pointer");
  std::vector<settings::PointerLaneSettings> lanes;
  std::vector<DeviceConfig> devices(elements.size());
  for (std::size_t i = 0; i < elements.size(); ++i) {
    lanes.push_back(ReadPointerElement(elements[i], session->engine.rendering, &devices[i]));
    for (std::size_t j = 0; j < i; ++j) {
      if (lanes[j].pointer.body == lanes[i].pointer.body) {
        elements[i]
            .Require("body", "")
            .Fail(fmt::format("\"{}\" is also pointers[{}].body", lanes[i].pointer.body, j),
                  "a distinct mocap body per pointer");
      }
    }
  }
  CheckDistinctDevices(elements, devices);
  session->engine.pointer = lanes[0].pointer;
  session->device = devices[0];
  if (lanes.size() == 1) {
    session->engine.rendering = lanes[0].rendering;
    return;
  }
  session->engine.pointers = std::move(lanes);
  session->pointer_devices = std::move(devices);
}

// "gravity": three components within kMaxGravity.
void ReadGravity(const Node& root, Session* session) {
  if (const auto gravity = root.Find("gravity")) {
    const std::vector<double> g = gravity->Numbers(3, "[gx, gy, gz] (m/s^2)");
    session->gravity = Vec3(g[0], g[1], g[2]);
    if (!(session->gravity->cwiseAbs().maxCoeff() <= kMaxGravity)) {
      gravity->Fail(FormatNumbers(g.data(), 3) + " m/s^2",
                    "components in [-1000, 1000] m/s^2 (100 g)");
    }
  }
}

// Every pointer's device (or the one device) that is real hardware requires real-time mode.
void RequireRealtimeForRealDevices(const Node& root, Session* session) {
  if (session->pointer_devices.empty()) {
    RequireRealtimeForRealDevice(root, session->device.type, &session->engine);
  } else {
    for (const DeviceConfig& device : session->pointer_devices) {
      RequireRealtimeForRealDevice(root, device.type, &session->engine);
    }
  }
}

// Keys that fill Session itself or the engine settings, then the blocks.
Session ParseDocument(const nlohmann::json& document, const Context& context) {
  const Node root(context, document, "");
  root.ExpectObject(TopLevelKeys(), "a JSON object");
  Session session;
  session.file = context.origin();
  // A session that names no method gets the thesis' proposed method (chapter 4's local
  // dynamics, with the contact local model), not a baseline. Programs that build
  // engine::EngineSettings themselves keep its own default.
  session.engine.method = kDefaultSessionMethod;
  session.scene =
      root.Require("scene", "the MJCF scene's path (string)").ExistingFile("the MJCF scene file");
  internal::ReadFields(root, internal::kEngineFields, &session.engine);
  if (const auto method = root.Find("method")) CheckMethod(*method);
  if (const auto mode = root.Find("mode")) session.engine.mode = ParseMode(*mode);
  if (const auto keyframe = root.Find("keyframe")) session.keyframe = keyframe->String();
  ReadGravity(root, &session);
  ReadRendering(root, &session.engine.rendering);
  ReadMaterials(root, &session.engine.rendering);
  internal::ReadBlock(root, "safety", internal::kSafetyFields, &session.engine.safety);
  if (const auto pointers = root.Find("pointers")) {
    ReadPointers(root, *pointers, &session);
  } else {
    internal::ReadBlock(root, "pointer", internal::kPointerFields, &session.engine.pointer);
    session.device = internal::ParseDevice(
        root.Require("device", "an object with at least \"type\" (see docs/session-format.md)"));
    internal::CheckStiffnessLimit(root, session.device, session.engine.rendering.stiffness);
  }
  RequireRealtimeForRealDevices(root, &session);
  return session;
}

// Range checks live in the settings' own Validate(); the session adds where the value came from.
void ValidateSettings(const Session& session, const Context& context) {
  // Both name the key by its session path ("physics_dt", "device.hand.mass").
  try {
    session.engine.Validate();
    if (session.device.type == "hand") session.device.hand.Validate();
    for (std::size_t i = 0; i < session.pointer_devices.size(); ++i) {
      if (session.pointer_devices[i].type != "hand") continue;
      try {
        session.pointer_devices[i].hand.Validate();
      } catch (const InvalidArgument& e) {
        throw InvalidArgument(fmt::format("pointers[{}].{}", i, e.what()));
      }
    }
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", context.origin(), e.what()));
  }
}

fs::path AbsoluteFolder(const fs::path& folder) {
  return (folder.empty() ? fs::current_path() : fs::absolute(folder)).lexically_normal();
}

}  // namespace

Session ParseSession(const std::string& json_text, const fs::path& base_dir,
                     const std::vector<std::string>& overrides, const std::string& origin) {
  Context context(origin, AbsoluteFolder(base_dir));
  nlohmann::json document = internal::ParseJsonText(json_text, origin);
  if (!document.is_object()) {
    context.Fail("", "found " + internal::Describe(document),
                 "a JSON object {...} of session keys");
  }
  internal::ApplyOverrides(overrides, &document, &context);
  Session session = ParseDocument(document, context);
  ValidateSettings(session, context);
  return session;
}

Session LoadSession(const fs::path& file, const std::vector<std::string>& overrides) {
  const std::string origin = file.string();
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    throw InvalidArgument(fmt::format(
        "{}: session file does not exist or is not a regular file; expected the path of a "
        "session JSON file",
        origin));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw InvalidArgument(
        fmt::format("{}: cannot open the session file ({}); expected a readable file", origin,
                    std::generic_category().message(errno)));
  }
  std::stringstream text;
  text << in.rdbuf();
  return ParseSession(text.str(), fs::absolute(file).parent_path(), overrides, origin);
}

}  // namespace mrh::session
