// SPDX-License-Identifier: Apache-2.0
// Demo D1's run: the session on the engine with a recorder that follows every object, the
// pointer and the physics steps.
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "d1_impl.h"
#include "mrh/core/error.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

struct TableTop {
  double x = 0.0, y = 0.0, hx = 0.0, hy = 0.0, top = 0.0;
};

TableTop FindTable(const world::World& world) {
  for (int g = 0; g < world.num_geoms(); ++g) {
    const world::GeomInfo& info = world.geom(g);
    if (info.name != "table") continue;
    if (info.shape.type != geometry::ShapeType::kBox || !world.body(info.body).is_static) break;
    // An axis-aligned box (the generated scene's): its top is the surface objects rest on.
    const Pose X_WG = world.geom_pose(g);
    return {X_WG.p.x(), X_WG.p.y(), info.shape.size.x(), info.shape.size.y(),
            X_WG.p.z() + info.shape.size.z()};
  }
  throw SceneError(world.origin() + ": no static box geom named \"table\"; expected D1's table");
}

// Follows the objects (free bodies) after every step and the pointer every tick.
class D1Recorder final : public physics::Recorder {
 public:
  D1Recorder(const world::World& world, D1Run* run) : run_(run) {
    const TableTop table = FindTable(world);
    run->table_x = table.x;
    run->table_y = table.y;
    run->table_hx = table.hx;
    run->table_hy = table.hy;
    run->table_top = table.top;
    for (int b = 1; b < world.num_bodies(); ++b) {
      if (world.body(b).is_static || world.body(b).is_mocap) continue;
      bodies_.push_back(b);
      start_.push_back(world.body_state(b).p_WCm);
    }
    left_.assign(bodies_.size(), false);
    run->objects = static_cast<int>(bodies_.size());
  }

  void OnTick(const ir::TickRecord& tick) override {
    ++run_->recorded_ticks;
    run_->last_tick_t = std::max(run_->last_tick_t, tick.t);
    if (tick.contacts > 0) {
      ++run_->contact_ticks;
      ++period_contact_ticks_;
    }
    if (have_last_ && tick.t > last_t_) {
      const double v = (tick.X_WP.p - last_p_).norm() / (tick.t - last_t_);
      period_hand_speed_ = std::max(period_hand_speed_, v);
      if (tick.contacts > 0)
        run_->max_contact_hand_speed = std::max(run_->max_contact_hand_speed, v);
    }
    have_last_ = true;
    last_t_ = tick.t;
    last_p_ = tick.X_WP.p;
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    D1Step row{step.t, step.compute_ms,    step.sim_contacts,    step.neighbors,
               0.0,    period_hand_speed_, period_contact_ticks_};
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const world::BodyState s = world.body_state(bodies_[i]);
      const double speed = s.V_WCm.v.norm();
      row.max_body_speed = std::max(row.max_body_speed, speed);
      if (speed > run_->max_body_speed) {
        run_->max_body_speed = speed;
        run_->fastest_body = world.body(bodies_[i]).name;
        run_->fastest_t = step.t;
      }
      run_->max_drop = std::max(run_->max_drop, start_[i].z() - s.p_WCm.z());
      run_->max_displacement = std::max(run_->max_displacement, (s.p_WCm - start_[i]).norm());
      const bool on = std::abs(s.p_WCm.x() - run_->table_x) <= run_->table_hx &&
                      std::abs(s.p_WCm.y() - run_->table_y) <= run_->table_hy &&
                      s.p_WCm.z() > run_->table_top;
      if (!on && !left_[i]) {
        left_[i] = true;
        ++run_->off_table;
        if (run_->first_off_table.empty()) {
          run_->first_off_table = fmt::format(
              "{} at t = {:.2f} s, centre of mass ({:.3f}, {:.3f}, {:.3f}) m",
              world.body(bodies_[i]).name, step.t, s.p_WCm.x(), s.p_WCm.y(), s.p_WCm.z());
        }
      }
    }
    run_->max_hand_speed = std::max(run_->max_hand_speed, period_hand_speed_);
    run_->steps.push_back(row);
    period_hand_speed_ = 0.0;
    period_contact_ticks_ = 0;
  }

 private:
  D1Run* run_;
  std::vector<int> bodies_;
  std::vector<Vec3> start_;
  std::vector<bool> left_;
  bool have_last_ = false;
  double last_t_ = 0.0;
  Vec3 last_p_ = Vec3::Zero();
  double period_hand_speed_ = 0.0;
  int period_contact_ticks_ = 0;
};

}  // namespace

D1Run RunD1Session(const session::Session& session) {
  auto engine = session::MakeEngine(session);
  D1Run run;
  run.steps.reserve(static_cast<std::size_t>(
      std::ceil(session.engine.duration / session.engine.physics_dt) + 16));
  D1Recorder recorder(engine->world(), &run);
  run.stats = engine->Run(&recorder);
  for (const physics::BodyImpulseTotal& impulse : run.stats.impulses) {
    if (impulse.linear.norm() > 0.0 || impulse.angular.norm() > 0.0) ++run.touched_objects;
  }
  return run;
}

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0 / 1e6;  // ru_maxrss is in KiB on Linux
}

}  // namespace mrh::experiments::internal
