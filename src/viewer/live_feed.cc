// SPDX-License-Identifier: Apache-2.0
// LiveFeed: converts engine records into what the UI draws and publishes them lock-free.
#include "viewer/live_feed.h"

#include "mrh/ir/snapshot.h"

namespace mrh::viewer::internal {
namespace {

// The world point of body-fixed p_B on neighbor `motion`; false for an index out of range.
bool BodyPoint(const ir::PhysicsSnapshot& s, int motion, const Vec3& p_B, Vec3* p_W) {
  if (motion < 0 || static_cast<std::size_t>(motion) >= s.bodies.size()) return false;
  *p_W = s.bodies[static_cast<std::size_t>(motion)].X_WB * p_B;
  return true;
}

}  // namespace

LiveFeed::LiveFeed(std::size_t tick_capacity) : ticks_(tick_capacity) {}

void LiveFeed::PublishWorld(const world::World& world) {
  world::CaptureSceneState(world, &scenes_.write_slot());
  scenes_.Publish();
}

void LiveFeed::OnTick(const ir::TickRecord& tick) {
  TickSample sample;
  sample.pointer = tick.pointer;
  sample.t = time_offset_ + tick.t;
  sample.X_WP = tick.X_WP;
  sample.X_WQ = tick.X_WQ;
  sample.displayed_W = tick.displayed_W;
  sample.rendered_W = tick.rendered_W;
  sample.contacts = tick.contacts;
  sample.safety_bits = tick.safety_bits;
  if (!ticks_.TryPush(sample)) dropped_.fetch_add(1, std::memory_order_relaxed);
}

void LiveFeed::OnStep(const physics::StepRecord& step, const world::World& world) {
  world::SceneState& state = scenes_.write_slot();
  world::CaptureSceneState(world, &state);
  state.t += time_offset_;
  scenes_.Publish();
  step_ms_.store(step.compute_ms, std::memory_order_relaxed);
  steps_.fetch_add(1, std::memory_order_relaxed);
}

void LiveFeed::OnSnapshot(const ir::PhysicsSnapshot& snapshot) {
  IrView& view = irs_.write_slot();
  view.step = snapshot.step;
  view.planes.clear();
  view.object_points_W.clear();
  view.pointer_points_P.clear();
  // 3-DOF plane IR: one plane per neighbor geom, through its closest point.
  for (const ir::PointContact& c : snapshot.contacts) {
    Vec3 p_W;
    if (!BodyPoint(snapshot, c.motion, c.p_BC, &p_W)) continue;
    view.planes.push_back(IrPlane{p_W, c.n_W});
    view.object_points_W.push_back(p_W);
  }
  // 6-DOF geometric IR: one plane per geom pair, its contact points fixed on the pointer.
  for (const ir::GeometricPair& pair : snapshot.pairs) {
    Vec3 p_W;
    if (!BodyPoint(snapshot, pair.motion, pair.p_BC, &p_W)) continue;
    view.planes.push_back(IrPlane{p_W, pair.n_W});
    for (int i = 0; i < pair.num_points; ++i) {
      const std::size_t k = static_cast<std::size_t>(pair.first_point + i);
      if (k < snapshot.points.size()) view.pointer_points_P.push_back(snapshot.points[k].p_PV);
    }
  }
  irs_.Publish();
}

}  // namespace mrh::viewer::internal
