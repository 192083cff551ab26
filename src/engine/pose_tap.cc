// SPDX-License-Identifier: Apache-2.0
// PoseTap: copies the world's body poses into the engine's triple buffer after every step.
#include "pose_tap.h"

#include <cstddef>

#include "mrh/world/world.h"

namespace mrh::engine::internal {

BodyPoses InitialBodyPoses(const world::World& world) {
  BodyPoses poses;
  poses.t = world.time();
  poses.X_WB.resize(static_cast<std::size_t>(world.num_bodies()));
  for (int id = 0; id < world.num_bodies(); ++id) {
    poses.X_WB[static_cast<std::size_t>(id)] = world.body_state(id).X_WB;
  }
  return poses;
}

void PoseTap::OnTick(const ir::TickRecord& tick) {
  if (next_ != nullptr) next_->OnTick(tick);
}

void PoseTap::OnStep(const physics::StepRecord& step, const world::World& world) {
  BodyPoses& slot = poses_->write_slot();
  slot.step = step.step;
  slot.t = step.t;
  // Every slot holds num_bodies poses from InitialBodyPoses: overwrite in place, no allocation.
  for (std::size_t id = 0; id < slot.X_WB.size(); ++id) {
    slot.X_WB[id] = world.body_state(static_cast<int>(id)).X_WB;
  }
  poses_->Publish();
  if (next_ != nullptr) next_->OnStep(step, world);
}

void PoseTap::OnSnapshot(const ir::PhysicsSnapshot& snapshot) {
  if (next_ != nullptr) next_->OnSnapshot(snapshot);
}

}  // namespace mrh::engine::internal
