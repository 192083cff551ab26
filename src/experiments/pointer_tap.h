// SPDX-License-Identifier: Apache-2.0
// A recorder for experiments with several pointers: each pointer's displayed force per tick and
// the centre of mass of named bodies per physics step.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/engine/engine.h"

namespace mrh::experiments::internal {

/// Keeps every tick's displayed force of every pointer and, after every physics step, the
/// centres of mass of the bodies named at construction. Not for the RT path: it allocates.
class PointerTap final : public physics::Recorder {
 public:
  /// `bodies`: scene body names whose centre of mass is recorded, in this order.
  explicit PointerTap(std::vector<std::string> bodies) : names_(std::move(bodies)) {}

  void OnTick(const ir::TickRecord& tick) override;
  /// @throws mrh::InvalidArgument naming a body the scene does not have.
  void OnStep(const physics::StepRecord& step, const world::World& world) override;

  struct Sample {
    double t;  ///< s
    Vec3 f;    ///< displayed force (N, world frame)
  };

  struct Step {
    double t;             ///< s
    std::vector<Vec3> p;  ///< centres of mass of the named bodies (m)
  };

  /// Ticks of pointer `i` (empty for a pointer the session does not have).
  const std::vector<Sample>& forces(int i) const;

  const std::vector<Step>& steps() const { return steps_; }

  /// Mass of the named body `i` (kg); valid after the first step.
  double mass(int i) const { return masses_.at(static_cast<std::size_t>(i)); }

 private:
  std::vector<std::string> names_;
  std::vector<int> ids_;
  std::vector<double> masses_;
  std::vector<std::vector<Sample>> forces_;
  std::vector<Step> steps_;
};

/// A pointer's force over a window of time.
struct ForceStats {
  double mean_norm = 0.0;    ///< mean |f| (N)
  double sd_norm = 0.0;      ///< standard deviation of |f| (N)
  Vec3 mean = Vec3::Zero();  ///< mean f (N)
  int n = 0;                 ///< ticks in the window
};

/// Statistics of the samples with `from` <= t <= `to` (all zero when there are none).
ForceStats WindowForce(const std::vector<PointerTap::Sample>& samples, double from, double to);

}  // namespace mrh::experiments::internal
