// SPDX-License-Identifier: Apache-2.0
// Session → world and engine. Kept apart from the parser so parsing links without them.
#include <string>
#include <string_view>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/engine/method.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::session {
namespace {

bool StartsWithPath(std::string_view message, const std::filesystem::path& path) {
  const std::string text = path.string();
  return !text.empty() && message.starts_with(text) && message.size() > text.size() &&
         message[text.size()] == ':';
}

// Errors of the device and the engine name a session key or a scene item; every error starts
// with the file to edit: the session's, unless it already names a scene or data file.
template <typename Build>
auto WithFile(const Session& session, Build&& build) {
  try {
    return build();
  } catch (const Error& e) {
    const std::string_view message = e.what();
    for (const auto* path :
         {&session.file, &session.scene, &session.device.trajectory, &session.device.replay}) {
      if (StartsWithPath(message, *path)) throw;
    }
    const std::string text = session.file.string() + ": " + std::string(message);
    if (dynamic_cast<const SceneError*>(&e) != nullptr) throw SceneError(text);
    if (dynamic_cast<const InvalidArgument*>(&e) != nullptr) throw InvalidArgument(text);
    throw RuntimeError(text);
  }
}

// Pointers 1, 2, ... of a several-pointer session.
std::vector<std::string> MorePointerBodies(const Session& session) {
  std::vector<std::string> bodies;
  for (std::size_t i = 1; i < session.engine.pointers.size(); ++i) {
    bodies.push_back(session.engine.pointers[i].pointer.body);
  }
  return bodies;
}

}  // namespace

// The timestep is left to the engine: it sets physics_dt, or haptic_dt for single-rate methods.
world::World LoadWorld(const Session& session) {
  const settings::RenderingSettings& r = session.engine.rendering;
  // The method says how (e.g. virtual-coupling's pointer is a dynamic tool inside MuJoCo).
  const std::optional<engine::MethodDescriptor> method = engine::FindMethod(session.engine.method);
  const engine::MethodWorldNeeds needs = method ? method->world : engine::MethodWorldNeeds{};
  world::World world = world::World::LoadFile(
      session.scene, world::LoadOptions{.pointer_body = session.engine.pointer.body,
                                        .more_pointer_bodies = MorePointerBodies(session),
                                        .dynamic_pointer = needs.dynamic_pointer,
                                        .tool_mass = r.tool_mass,
                                        .tool_inertia = r.tool_inertia.value_or(Vec3::Zero()),
                                        .penalty_contacts = needs.penalty_contacts});
  if (!session.keyframe.empty()) world.ApplyKeyframe(session.keyframe);
  if (session.gravity) world.set_gravity(*session.gravity);
  return world;
}

std::unique_ptr<engine::Engine> MakeEngine(const Session& session) {
  if (!session.pointer_devices.empty()) {
    std::vector<std::unique_ptr<device::Device>> devices;
    std::vector<device::Calibration> calibrations;
    for (std::size_t i = 0; i < session.pointer_devices.size(); ++i) {
      devices.push_back(WithFile(session, [&] {
        return MakePointerDevice(session, static_cast<int>(i));
      }));
      calibrations.push_back(session.pointer_devices[i].calibration);
    }
    world::World world = LoadWorld(session);
    return WithFile(session, [&] {
      return std::make_unique<engine::Engine>(std::move(world), std::move(devices), calibrations,
                                              session.engine);
    });
  }
  std::unique_ptr<device::Device> device = WithFile(session, [&] {
    return MakeDevice(session);
  });
  return MakeEngine(session, std::move(device));
}

std::unique_ptr<engine::Engine> MakeEngine(const Session& session,
                                           std::unique_ptr<device::Device> device) {
  world::World world = LoadWorld(session);
  return WithFile(session, [&] {
    return std::make_unique<engine::Engine>(std::move(world), std::move(device),
                                            session.device.calibration, session.engine);
  });
}

}  // namespace mrh::session
