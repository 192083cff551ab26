// SPDX-License-Identifier: Apache-2.0
#include "island_sync.h"

#include <algorithm>

#include "mrh/core/spatial.h"
#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {
namespace {

bool Contains(const std::vector<int>& list, int body) {
  return std::find(list.begin(), list.end(), body) != list.end();
}

// A rigid body's pose `t` seconds on with constant COM twist V (no forces).
Pose Coast(const Pose& X_WB, const Vec3& p_BCm, const Twist& V, double t) {
  const Quat q = (QuatFromRotationVector(t * V.w) * X_WB.q).normalized();
  const Vec3 p_WCm = X_WB * p_BCm + t * V.v;
  return Pose{p_WCm - q * p_BCm, q};
}

}  // namespace

IslandSync::IslandSync(world::World* world, double physics_dt)
    : world_(world), physics_dt_(physics_dt) {
  const auto capacity = static_cast<std::size_t>(world_->num_bodies());
  for (std::vector<int>* v : {&sent_last_, &sent_before_, &failed_, &owned_, &owned_before_}) {
    v->reserve(capacity);
  }
  written_.reserve(capacity);
}

void IslandSync::Overwrite(const ir::HapticReport& report) {
  failed_.clear();
  written_.clear();
  const bool touched = !report.impulses.empty();
  owned_before_.swap(owned_);
  owned_.clear();
  for (const ir::LocalBodyState& state : report.local_states) {
    if (!Contains(sent_before_, state.body)) continue;
    if (!touched && !Contains(owned_before_, state.body)) {
      failed_.push_back(state.body);
      continue;
    }
    owned_.push_back(state.body);
    if (Write(state, report.local_states, 0.0)) {
      ++counters_.overwrites;
      written_.push_back(state);
    } else {
      ++counters_.overwrite_failures;
      failed_.push_back(state.body);
    }
  }
  ApplyReportImpulses(*world_, report, physics_dt_);
}

void IslandSync::HoldOwned(double coast_s) {
  for (const ir::LocalBodyState& s : written_) (void)Write(s, written_, coast_s);
}

bool IslandSync::Write(const ir::LocalBodyState& state, std::span<const ir::LocalBodyState> states,
                       double coast_s) {
  const world::BodyInfo& info = world_->body(state.body);
  const Pose X_WB =
      coast_s == 0.0 ? state.X_WB : Coast(state.X_WB, info.p_BCm, state.V_WCm, coast_s);
  if (info.free) return world_->SetBodyState(state.body, X_WB, state.V_WCm);
  const auto parent = std::find_if(states.begin(), states.end(), [&](const ir::LocalBodyState& s) {
    return s.body == info.parent;
  });
  if (parent == states.end()) {
    const world::BodyState p = world_->body_state(info.parent);
    return world_->SetBodyStateInParent(state.body, X_WB, state.V_WCm, p.X_WB, p.V_WCm);
  }
  const Pose X_WP =
      coast_s == 0.0 ? parent->X_WB
                     : Coast(parent->X_WB, world_->body(info.parent).p_BCm, parent->V_WCm, coast_s);
  return world_->SetBodyStateInParent(state.body, X_WB, state.V_WCm, X_WP, parent->V_WCm);
}

std::uint32_t IslandSync::Export(world::ContactExporter& exporter, std::span<const int> seeds,
                                 std::span<const int> motions, ir::PhysicsSnapshot* out) {
  const std::uint32_t status = exporter.Export(seeds, motions, &out->local_model);
  sent_before_.swap(sent_last_);
  sent_last_.clear();
  for (ir::LocalIslandBody& b : out->local_model.bodies) {
    b.reset = Contains(failed_, b.body);
    sent_last_.push_back(b.body);
  }
  counters_.last_island_bodies = static_cast<int>(out->local_model.bodies.size());
  counters_.last_island_contacts = static_cast<int>(out->local_model.contacts.size());
  return status;
}

}  // namespace mrh::physics::internal
