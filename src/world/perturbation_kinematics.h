// SPDX-License-Identifier: Apache-2.0
// What the Perturber reads of a body's joints: which bodies its forward-skip path handles, and
// the velocities a step would give them.
#pragma once

#include <mujoco/mujoco.h>

#include "mrh/core/spatial.h"

namespace mrh::world::internal {

/// One free joint.
bool IsFreeBody(const mjModel& m, int body);

/// Slide joints only, on a parent that cannot move: the body never rotates and its COM velocity
/// is the sum of the joint axes (fixed in the world) times the joint speeds.
bool IsSlideBody(const mjModel& m, int body);

/// The COM twist mj_step would produce from the forwarded state in `d` with accelerations `qacc`
/// (mj_Euler without damping: qvel + dt·qacc, then mj_integratePos), read as World::body_state
/// would read it after the step, for one free or slide body. `dt` = 0 reads the current one.
Twist TwistAfterEuler(const mjModel& m, const mjData& d, int body, double dt, const mjtNum* qacc);

}  // namespace mrh::world::internal
