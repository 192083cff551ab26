// SPDX-License-Identifier: Apache-2.0
// The engine's recorder in the viewer: hands ticks, world state and IR to the UI without locks.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "mrh/core/spsc_ring.h"
#include "mrh/core/triple_buffer.h"
#include "mrh/engine/engine.h"
#include "mrh/world/scene_renderer.h"

namespace mrh::viewer::internal {

/// One haptic tick as the UI sees it (world frame).
struct TickSample {
  int pointer = 0;     ///< whose tick (the session's pointer index)
  double t = 0.0;      ///< s on the viewer clock (continues across engine restarts)
  Pose X_WP;           ///< pointer pose
  Pose X_WQ;           ///< the method's proxy pose (= X_WP for methods without a proxy)
  Wrench displayed_W;  ///< after the safety layer (what a device would display)
  Wrench rendered_W;   ///< what the method rendered
  int contacts = 0;
  std::uint32_t safety_bits = 0;
};

/// A plane of the IR, world frame.
struct IrPlane {
  Vec3 p_W = Vec3::Zero();   ///< a point on the plane (on the object) (m)
  Vec3 n_W = Vec3::UnitZ();  ///< unit normal, object → pointer
};

/// The IR of the newest physics snapshot.
struct IrView {
  std::int64_t step = -1;
  std::vector<IrPlane> planes;
  std::vector<Vec3> object_points_W;   ///< plane points on the objects (m, world)
  std::vector<Vec3> pointer_points_P;  ///< contact points fixed on the pointer (m, pointer frame)
};

/// Recorder given to Engine::Start. The producer side runs on the engine's physics thread (and
/// on the UI thread before Start, to publish the initial state); the consumer side on the UI
/// thread. Ticks cross in an SPSC ring (dropped and counted when full), the world state and the
/// IR in triple buffers: nothing ever waits.
class LiveFeed final : public physics::Recorder {
 public:
  /// `tick_capacity`: ticks the ring holds between two UI frames.
  explicit LiveFeed(std::size_t tick_capacity);

  /// Producer, before Engine::Start: the viewer-clock time of the new engine's t = 0 (s).
  void set_time_offset(double t0) { time_offset_ = t0; }

  /// Producer, before Engine::Start: publishes the world's state as the first scene.
  void PublishWorld(const world::World& world);

  void OnTick(const ir::TickRecord& tick) override;
  void OnStep(const physics::StepRecord& step, const world::World& world) override;
  void OnSnapshot(const ir::PhysicsSnapshot& snapshot) override;

  /// Consumer: the next tick, if any.
  bool PopTick(TickSample* sample) { return ticks_.TryPop(sample); }

  /// Consumer: takes the newest scene state; returns true if it is new.
  bool UpdateScene() { return scenes_.Update(); }

  const world::SceneState& scene() const { return scenes_.read_slot(); }

  /// Consumer: takes the newest IR; returns true if it is new.
  bool UpdateIr() { return irs_.Update(); }

  const IrView& ir() const { return irs_.read_slot(); }

  /// Physics steps so far, over all engines (any thread).
  std::int64_t steps() const { return steps_.load(std::memory_order_relaxed); }

  /// Wall time of the last physics step (ms, any thread).
  double step_ms() const { return step_ms_.load(std::memory_order_relaxed); }

  /// Ticks dropped because the UI fell behind (any thread).
  std::int64_t dropped_ticks() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  double time_offset_ = 0.0;
  SpscRing<TickSample> ticks_;
  TripleBuffer<world::SceneState> scenes_;
  TripleBuffer<IrView> irs_;
  std::atomic<std::int64_t> steps_{0};
  std::atomic<double> step_ms_{0.0};
  std::atomic<std::int64_t> dropped_{0};
};

}  // namespace mrh::viewer::internal
