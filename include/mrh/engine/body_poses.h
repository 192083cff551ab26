// SPDX-License-Identifier: Apache-2.0
// The bodies' poses after a physics step, as a running engine hands them to other threads.
#pragma once

#include <cstdint>
#include <vector>

#include "mrh/core/spatial.h"

namespace mrh::engine {

/// Every body's pose at the end of one physics step: what a renderer of the scene draws. Filled
/// by the engine (Engine::ReadBodyPoses); indexed by body id, as world::World numbers bodies
/// (0 is the world body; take the names from Engine::world().body(id).name before the run).
struct BodyPoses {
  std::int64_t step = -1;  ///< physics step index; -1: the scene's initial state, before any step
  double t = 0.0;          ///< simulated time at the end of that step (s)
  /// Body frame pose in the world (m; body → world rotation), the MuJoCo body frame as the
  /// scene places it (not the centre of mass). Static and mocap bodies included.
  std::vector<Pose> X_WB;
};

}  // namespace mrh::engine
