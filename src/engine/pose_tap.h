// SPDX-License-Identifier: Apache-2.0
// PoseTap: a recorder in front of the caller's that publishes every step's body poses.
#pragma once

#include "mrh/core/triple_buffer.h"
#include "mrh/engine/body_poses.h"
#include "mrh/physics/recorder.h"

namespace mrh::engine::internal {

/// The first body poses a run publishes: the world's current state, step -1.
BodyPoses InitialBodyPoses(const world::World& world);

/// Sits between the physics side and the caller's recorder (`next`, may be null): forwards every
/// record, and after each step writes the world's body poses into `poses` and publishes them.
/// Physics thread (or the lockstep loop) only; publishing never blocks or allocates (the slots
/// are sized by InitialBodyPoses), so readers never hold up either thread.
class PoseTap final : public physics::Recorder {
 public:
  explicit PoseTap(TripleBuffer<BodyPoses>* poses) : poses_(poses) {}

  void set_next(physics::Recorder* next) { next_ = next; }

  void OnTick(const ir::TickRecord& tick) override;
  void OnStep(const physics::StepRecord& step, const world::World& world) override;
  void OnSnapshot(const ir::PhysicsSnapshot& snapshot) override;

 private:
  TripleBuffer<BodyPoses>* poses_;
  physics::Recorder* next_ = nullptr;
};

}  // namespace mrh::engine::internal
