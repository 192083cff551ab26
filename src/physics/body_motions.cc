// SPDX-License-Identifier: Apache-2.0
// BodyMotions: previous poses and snapshot body entries.
#include "body_motions.h"

#include "mrh/world/world.h"

namespace mrh::physics::internal {

BodyMotions::BodyMotions(const world::World& world)
    : previous_X_WB_(static_cast<std::size_t>(world.num_bodies())) {
  CapturePreviousPoses(world);
}

void BodyMotions::CapturePreviousPoses(const world::World& world) {
  for (int b = 0; b < world.num_bodies(); ++b) {
    previous_X_WB_[static_cast<std::size_t>(b)] = world.body_state(b).X_WB;
  }
}

int BodyMotions::Add(const world::World& world, int body, ir::PhysicsSnapshot* out) const {
  for (std::size_t i = 0; i < out->bodies.size(); ++i) {
    if (out->bodies[i].body == body) return static_cast<int>(i);
  }
  const world::BodyState state = world.body_state(body);
  const world::BodyInfo& info = world.body(body);
  ir::BodyMotion m;
  m.body = body;
  m.X_WB_prev = previous_X_WB_[static_cast<std::size_t>(body)];
  m.X_WB = state.X_WB;
  m.p_BCm = info.p_BCm;
  m.V_WCm = state.V_WCm;
  m.is_static = info.is_static || info.is_mocap;
  if (!out->bodies.PushBack(m)) {
    out->status |= ir::kStatusBodiesFull;
    return -1;
  }
  return static_cast<int>(out->bodies.size() - 1);
}

}  // namespace mrh::physics::internal
