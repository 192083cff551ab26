// SPDX-License-Identifier: Apache-2.0
// T3.1's edge → face motion rendered by the B5 penalty sum (Berkelman & Hollis 2000, thesis
// ref. [43]), public engine API only.
#include <cmath>
#include <memory>

#include "experiments_impl.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

class TickTap final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<ir::TickRecord> ticks;
};

}  // namespace

std::vector<ir::TickRecord> RunPenaltySumTicks(const session::Session& session) {
  session::Session s = session;
  s.engine.method = "penalty-sum";
  s.engine.mode = settings::Mode::kLockstep;
  engine::Engine engine(session::LoadWorld(s), session::MakeDevice(s), s.device.calibration,
                        s.engine);
  TickTap tap;
  tap.ticks.reserve(static_cast<std::size_t>(s.engine.duration / s.engine.haptic_dt) + 2);
  (void)engine.Run(&tap);
  return std::move(tap.ticks);
}

nlohmann::json CheckPenaltySumT31(const std::vector<ir::TickRecord>& ticks,
                                  const PenaltySumWindows& w, nlohmann::json* numbers) {
  // Σ k δ over the penetrating vertices: m k δ for m vertices at equal depth δ. Relative
  // tolerance: rounding of metre-scale poses (1e-12 m) against δ ~ 3e-4 m.
  constexpr double kRelTol = 1e-6;
  double edge_f = 0.0, face_f = 0.0;
  int edge_ticks = 0, face_ticks = 0;
  bool edge_ok = true, face_ok = true;
  for (const ir::TickRecord& tick : ticks) {
    const double f = tick.rendered_W.f.z();
    // As the proxy's onset check: the edge ticks with both vertices in the IR (the first tick
    // of the hold still renders the IR of the previous step, one vertex).
    if (tick.t >= w.edge_hold[0] && tick.t < w.edge_hold[1] && tick.contacts == 2) {
      ++edge_ticks;
      edge_f = f;
      edge_ok = edge_ok && std::abs(f - 2.0 * w.k * w.edge_depth) <= kRelTol * f;
    }
    if (tick.t >= w.face_hold) {
      ++face_ticks;
      face_f = f;
      face_ok =
          face_ok && tick.contacts == 4 && std::abs(f - 4.0 * w.k * w.face_depth) <= kRelTol * f;
    }
  }
  // Force per unit depth: the proxy keeps k_t; the sum goes from 2k (edge) to 4k (face).
  const double edge_stiffness = edge_f / w.edge_depth, face_stiffness = face_f / w.face_depth;
  (*numbers)["penalty_sum_edge_ticks"] = edge_ticks;
  (*numbers)["penalty_sum_edge_force_N"] = edge_f;
  (*numbers)["penalty_sum_face_force_N"] = face_f;
  (*numbers)["penalty_sum_edge_stiffness_N_per_m"] = edge_stiffness;
  (*numbers)["penalty_sum_face_stiffness_N_per_m"] = face_stiffness;
  (*numbers)["penalty_sum_stiffness_jump"] = face_stiffness / edge_stiffness;
  return {{"penalty_sum_edge_2k_depth", edge_ok && edge_ticks > 0},
          {"penalty_sum_face_4k_depth", face_ok && face_ticks > 0}};
}

}  // namespace mrh::experiments::internal
