// SPDX-License-Identifier: Apache-2.0
// Saving and restoring the minimal MuJoCo state that makes the next step bit-identical.
#include <mujoco/mujoco.h>

#include <type_traits>

#include "mrh/core/assert.h"
#include "mrh/world/world.h"
#include "world/world_impl.h"

namespace mrh::world {

static_assert(std::is_same_v<mjtNum, double>, "snapshots store mjtNum as double");

Snapshot::Snapshot() = default;
Snapshot::~Snapshot() = default;
Snapshot::Snapshot(Snapshot&&) noexcept = default;
Snapshot& Snapshot::operator=(Snapshot&&) noexcept = default;

namespace {

// The fields of mjData that determine the next mj_step: MuJoCo's integration state (time, qpos,
// qvel, act, history, plugin state, warm start, controls, applied forces, active equalities,
// mocap poses, user data). Restoring exactly these reproduces the step bit for bit; everything
// else in mjData is recomputed from them.
constexpr int kStateFields = mjSTATE_INTEGRATION;

}  // namespace

namespace internal {

std::size_t SnapshotSize(const mjModel& m) {
  return static_cast<std::size_t>(mj_stateSize(&m, kStateFields));
}

}  // namespace internal

Snapshot World::MakeSnapshot() const {
  Snapshot snapshot;
  snapshot.data_.assign(impl_->snapshot_size, 0.0);
  Save(&snapshot);
  return snapshot;
}

void World::Save(Snapshot* snapshot) const {
  MRH_DEMAND(snapshot != nullptr && snapshot->data_.size() == impl_->snapshot_size);
  mj_getState(impl_->model.get(), impl_->data.get(), snapshot->data_.data(), kStateFields);
}

void World::Restore(const Snapshot& snapshot) {
  MRH_DEMAND(snapshot.data_.size() == impl_->snapshot_size);
  mj_setState(impl_->model.get(), impl_->data.get(), snapshot.data_.data(), kStateFields);
  // Poses and velocities follow from the restored qpos/qvel on the next query. A full
  // mj_forward is not needed: mj_step recomputes everything else, and skipping it keeps
  // perturbation loops (restore, perturb, step) cheap.
  impl_->kinematics_stale = true;
}

}  // namespace mrh::world
