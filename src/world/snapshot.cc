// SPDX-License-Identifier: Apache-2.0
// Saving and restoring the minimal MuJoCo state that makes the next step bit-identical.
#include <mujoco/mujoco.h>

#include <algorithm>
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

// The fields of mjData that determine the next mj_step (DEPENDENCIES.md: restoring exactly these
// reproduces the step bit for bit). Everything else in mjData is recomputed from them. `visit`
// is called with each field's address and length, in a fixed order.
template <typename Data, typename Visit>
void ForEachStateField(const mjModel& m, Data* d, Visit visit) {
  visit(&d->time, 1);
  visit(d->qpos, m.nq);
  visit(d->qvel, m.nv);
  visit(d->act, m.na);
  visit(d->qacc_warmstart, m.nv);
  visit(d->ctrl, m.nu);
  visit(d->qfrc_applied, m.nv);
  visit(d->xfrc_applied, 6 * m.nbody);
  visit(d->mocap_pos, 3 * m.nmocap);
  visit(d->mocap_quat, 4 * m.nmocap);
}

}  // namespace

namespace internal {

std::size_t SnapshotSize(const mjModel& m) {
  // The lengths of the fields in ForEachStateField; Save() checks that they agree.
  return static_cast<std::size_t>(1 + m.nq + 3 * m.nv + m.na + m.nu + 6 * m.nbody + 7 * m.nmocap);
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
  double* out = snapshot->data_.data();
  ForEachStateField(*impl_->model, static_cast<const mjData*>(impl_->data.get()),
                    [&out](const mjtNum* field, int n) {
                      out = std::copy_n(field, n, out);
                    });
  MRH_ASSERT(out == snapshot->data_.data() + snapshot->data_.size());
}

void World::Restore(const Snapshot& snapshot) {
  MRH_DEMAND(snapshot.data_.size() == impl_->snapshot_size);
  const double* in = snapshot.data_.data();
  ForEachStateField(*impl_->model, impl_->data.get(), [&in](mjtNum* field, int n) {
    std::copy_n(in, n, field);
    in += n;
  });
  // Poses and velocities follow from the restored qpos/qvel on the next query. A full
  // mj_forward is not needed: mj_step recomputes everything else, and skipping it keeps
  // perturbation loops (restore, perturb, step) cheap.
  impl_->kinematics_stale = true;
}

}  // namespace mrh::world
