// SPDX-License-Identifier: Apache-2.0
// Session → world and engine. Kept apart from the parser so parsing links without them.
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::session {

// The timestep is left to the engine: it sets physics_dt, or haptic_dt for single-rate methods.
world::World LoadWorld(const Session& session) {
  world::World world = world::World::LoadFile(
      session.scene, world::LoadOptions{.pointer_body = session.engine.pointer.body});
  if (!session.keyframe.empty()) world.ApplyKeyframe(session.keyframe);
  if (session.gravity) world.set_gravity(*session.gravity);
  return world;
}

std::unique_ptr<engine::Engine> MakeEngine(const Session& session) {
  return std::make_unique<engine::Engine>(LoadWorld(session), MakeDevice(session),
                                          session.device.calibration, session.engine);
}

}  // namespace mrh::session
